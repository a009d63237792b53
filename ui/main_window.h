// The workstation window: a composer of one panel per step (Robot, Plan,
// Acquire, Measure, Calibrate, Validate) around one SessionState, with the step list
// and the File menu (new, open, open demo, reload, recent sessions). The panels
// own their work; this class only wires them together.
//
//   MainWindow window;
//   window.OpenSession("build/demo");
//   window.ShowStep(Step::kCalibrate);
#pragma once

#include <QMainWindow>

#include "ui/session_state.h"

class QMenu;
class QStackedWidget;

namespace hexcal::ui {

class AcquirePanel;
class BackgroundJob;
class CalibratePanel;
class MeasurePanel;
class PlanPanel;
class RobotPanel;
class StepList;
class ValidatePanel;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);

  SessionState* Session() const { return session_; }
  RobotPanel* Robot() const { return robot_; }
  PlanPanel* Plan() const { return plan_; }
  AcquirePanel* Acquire() const { return acquire_; }
  MeasurePanel* Measure() const { return measure_; }
  CalibratePanel* Calibrate() const { return calibrate_; }
  ValidatePanel* Validate() const { return validate_; }

  bool OpenSession(const QString& dir);
  void ShowStep(Step step);
  // "robot", "plan", "acquire", "measure", "calibrate", "validate" (any case); false if unknown.
  bool ShowPanelNamed(const QString& name);
  // Resizes to `wanted`, within the screen's available area, at its top left.
  void FitScreen(const QSize& wanted);

 public slots:
  void NewSession();
  void OpenSessionDialog();
  void OpenDemoSession();

 private:
  void BuildMenus();
  void RememberRecent(const QString& dir);
  void FillRecentMenu();
  void closeEvent(QCloseEvent* event) override;
  void changeEvent(QEvent* event) override;  // focus in: SessionState::ReloadIfChanged

  SessionState* session_;
  StepList* steps_;
  QStackedWidget* stack_;
  RobotPanel* robot_;
  PlanPanel* plan_;
  AcquirePanel* acquire_;
  MeasurePanel* measure_;
  CalibratePanel* calibrate_;
  ValidatePanel* validate_;
  QMenu* recent_menu_;
  BackgroundJob* demo_job_;
};

}  // namespace hexcal::ui

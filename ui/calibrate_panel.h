// Calibrate step: the session calibration of `hexcal calibrate --session`
// (register the camera with the nominal robot, calibrate the 42 parameters,
// validate on held-out images) on a worker thread, with its progress (the
// images it measures, then the legs) and Cancel throughout.
// Shows, from results/report.json, one line of counts and closure, the lines
// the CLI prints folded in a run log (ui/run_log.h), the verdict
// (ui/verdict_view.h), and two tabs: the 42 parameters (nominal, calibrated,
// change, σ, identified) and the leg residuals of the nominal and the
// calibrated robot on the calibration poses.
//
//   auto* calibrate = new CalibratePanel(session);
//   calibrate->Run();  // a worker; Job()->Running() until the verdict is shown
#pragma once

#include <QWidget>

#include <vector>

#include "session/calibration_report.h"
#include "ui/qt_fwd.h"
#include "ui/session_state.h"

namespace hexcal::ui {

class RunLog;
class VerdictView;

class CalibratePanel : public QWidget {
  Q_OBJECT
 public:
  CalibratePanel(SessionState* session, QWidget* parent = nullptr);
  BackgroundJob* Job() const { return job_; }
  QTableWidget* ParameterTable() const { return parameters_; }
  VerdictView* VerdictWidget() const { return verdict_; }
  RunLog* Log() const { return run_log_; }
  const QString& LastOutcome() const { return outcome_; }

 public slots:
  void Run();
  void Refresh();
  // Another session was opened: no outcome or progress of the last one.
  void ResetForSession();

 private:
  void ArrangeWidgets();
  void Finish(const Status& status);
  void PlotResiduals();
  void SetUnitHeaders(const QString& unit);  // "nominal (cm)", ...
  void FillParameterTable(const std::vector<workflow::ParameterEstimate>& rows, const QString& unit);
  void SetOutcome(const QString& text);

  SessionState* session_;
  BackgroundJob* job_;
  QPushButton *run_, *cancel_;
  QProgressBar* progress_;
  QLabel *status_, *summary_;
  RunLog* run_log_;       // the lines the last run printed, folded
  VerdictView* verdict_;  // the verdict on results/report.json
  QTableWidget* parameters_;
  QtCharts::QChartView* residuals_;
  QString outcome_;
  QString idle_;  // the outcome line shown between runs
  bool outcome_from_job_ = false;  // outcome_ is a run's, shown until the step's state changes
  QString outcome_basis_;          // the step's state and sentence when the run's line was shown
};

}  // namespace hexcal::ui

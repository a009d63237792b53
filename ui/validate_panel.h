// Validate/Report step, two tabs: the verdict on the calibration
// (ui/verdict_view.h) with the held-out images' errors before (nominal robot)
// and after calibration, overall and per image (forward kinematics from the
// readings against the camera pose, from results/report.json); and the
// section 8 study of the session's poses (ui/study_view.h). Below both,
// export of the calibrated robot file and of the HTML report (`hexcal report`).
//
//   auto* validate = new ValidatePanel(session);
//   validate->ExportHtmlReport("report.html");  // as hexcal report
#pragma once

#include <QWidget>

#include "session/calibration_report.h"
#include "ui/qt_fwd.h"
#include "ui/session_state.h"

namespace hexcal::ui {

class StudyView;
class VerdictView;

class ValidatePanel : public QWidget {
  Q_OBJECT
 public:
  ValidatePanel(SessionState* session, QWidget* parent = nullptr);
  QTableWidget* SummaryTable() const { return summary_; }
  VerdictView* VerdictWidget() const { return verdict_; }
  StudyView* Study() const { return study_; }
  void ShowStudyTab();
  void ShowValidationTab();

 public slots:
  void Refresh();
  // Empty path: ask with a file dialog. Both read the session again first;
  // stale results only when the operator confirms (ConfirmStale).
  void ExportCalibratedRobot(const QString& path = {});
  void ExportHtmlReport(const QString& path = {});

 private:
  bool ResultsUsable(const QString& what);
  // `noun`: "image", or "pose" in a points session (measured by the tracker).
  void ShowValidation(const workflow::ValidationSummary& validation, const QString& unit, const QString& noun);

  SessionState* session_;
  VerdictView* verdict_;  // the verdict on results/report.json (ui/verdict_view.h)
  QLabel* status_;
  QTableWidget* summary_;
  QtCharts::QChartView *position_chart_, *orientation_chart_;
  QTabWidget* tabs_;
  StudyView* study_;  // the section 8 study (ui/study_view.h)
};

}  // namespace hexcal::ui

// Plan step: the IOOPS planner (core/ioops.h) on a worker thread with every
// option, progress and Cancel; the indices per iteration (paper figs 6,
// 10-12), live while it runs; the pose table (sortable, editable, delete and
// add poses); the leg lengths per pose against the strokes (fig. 8); export.
// The plan is the session's plan.csv, written on every change; the indices
// per iteration go to plan_history.csv (the columns of `hexcal plan --history`).
// A change that leaves recorded captures without their pose (a new plan, a
// pose edited or deleted) asks first: keep them (images with readings the
// calibration uses), archive them (moved to archive/), discard them, or
// cancel (workflow/plan_captures.h).
//
//   auto* plan = new PlanPanel(session);
//   plan->Options()->SetValue("poses", 16);
//   plan->Run();  // a worker; the session's plan.csv when it finishes
#pragma once

#include <QWidget>

#include "charts/chart_spec.h"
#include "core/ioops.h"
#include "core/planning_model.h"
#include "ui/qt_fwd.h"
#include "ui/session_state.h"
#include "workflow/plan_step.h"

namespace hexcal::ui {

class PlanOptionsForm;
class VisibilityForm;

class PlanPanel : public QWidget {
  Q_OBJECT
 public:
  PlanPanel(SessionState* session, QWidget* parent = nullptr);
  PlanOptionsForm* Options() const { return options_; }
  VisibilityForm* Visibility() const { return visibility_; }
  BackgroundJob* Job() const { return job_; }
  QTableWidget* PoseTable() const { return table_; }
  const QString& LastOutcome() const { return outcome_; }
  // plan.csv becomes `plan` (the change started from `seen`, the plan shown
  // by default), after asking what becomes of the captures it leaves without
  // their pose; false when cancelled or not written.
  bool ApplyPlan(const std::vector<Vector6d>& plan, const std::vector<Vector6d>* seen = nullptr);

 public slots:
  void Run();
  void Cancel();
  void Refresh();
  // Another session was opened: default options, no outcome of the last one.
  void ResetForSession();
  void DeleteSelectedPoses();
  void AddPose();
  void ExportPlan();

 signals:
  // A row of the pose table was picked: show that planned pose in 3D.
  void PoseSelected(int index);

 private:
  StatusOr<PlanningModel> Model() const;
  void Finish(const Status& status, const workflow::PlanOutcome& outcome);
  // One planner iteration on the live O1..O4 chart (log scale); iteration 0 starts it.
  void PlotIteration(const PlanIteration& step);
  void FillTable();
  void PlotLegLengths();
  void PlotHistory();
  void OnCellEdited(int row, int column);
  void SetOutcome(const QString& text);

  SessionState* session_;
  PlanOptionsForm* options_;
  VisibilityForm* visibility_;
  BackgroundJob* job_;
  QPushButton *run_, *cancel_;
  QProgressBar* progress_;
  QLabel* status_;
  QTableWidget* table_;
  QtCharts::QChartView *indices_chart_, *legs_chart_;
  charts::ChartSpec indices_;  // what indices_chart_ shows; the live plot appends to it
  QString outcome_;
  QString plan_note_;                   // what ApplyPlan did with the captures the new plan left
  bool outcome_from_job_ = false;       // outcome_ is the planner's, shown while plan.csv holds its plan
  std::vector<Vector6d> outcome_plan_;  // that plan
  // The plan when the planner started: the plan its result replaces, so that
  // a plan.csv another program wrote meanwhile is a conflict, not overwritten.
  std::vector<Vector6d> plan_at_start_;
  bool filling_ = false;
};

}  // namespace hexcal::ui

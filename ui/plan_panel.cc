#include "ui/plan_panel.h"

#include <QChartView>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>
#include <filesystem>
#include <set>

#include "charts/figures.h"
#include "charts/qt_chart.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/session_lock.h"
#include "session/readings_table.h"
#include "ui/background_job.h"
#include "ui/charts.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/option_form.h"
#include "ui/plan_options.h"
#include "ui/plan_visibility.h"
#include "ui/quantity_format.h"
#include "ui/table_cell.h"
#include "ui/text_wrap.h"
#include "workflow/plan_captures.h"
#include "workflow/plan_step.h"
#include "workflow/session_plan_model.h"

namespace hexcal::ui {
namespace {

constexpr const char* kIdleOutcome = "Choose the options and run the planner.";

const QStringList kColumns = {"#",  "x",  "y",  "z",  "q1 °", "q2 °", "q3 °",
                              "L1", "L2", "L3", "L4", "L5",   "L6",   "feasible"};

std::string HistoryPath(const SessionState& session) {
  return (std::filesystem::path(session.Dir().toStdString()) / "plan_history.csv").string();
}


// The text of FormatCoordinate (ui/quantity_format.h: "3.5000", not "3.5"
// beside "-18.17"), sorted by the number it reads as.
class CoordinateItem : public QTableWidgetItem {
 public:
  explicit CoordinateItem(const QString& text) : QTableWidgetItem(text) {}
  bool operator<(const QTableWidgetItem& other) const override {
    return text().toDouble() < other.text().toDouble();
  }
};

QTableWidgetItem* NumberItem(double value, bool editable) {
  return SetEditable(new CoordinateItem(FormatCoordinate(value)), editable);
}

}  // namespace

PlanPanel::PlanPanel(SessionState* session, QWidget* parent)
    : QWidget(parent),
      session_(session),
      options_(new PlanOptionsForm),
      visibility_(new VisibilityForm(session)),
      job_(new BackgroundJob(this)) {
  run_ = new QPushButton("Run planner");
  run_->setObjectName("plan_run");
  cancel_ = new QPushButton("Cancel");
  cancel_->setEnabled(false);
  progress_ = new QProgressBar;
  status_ = new QLabel(kIdleOutcome);
  status_->setTextFormat(Qt::PlainText);  // file names are shown as they are, never as HTML
  status_->setWordWrap(true);
  status_->setObjectName("plan_status");
  auto* export_button = new QPushButton("Export plan.csv…");
  connect(run_, &QPushButton::clicked, this, &PlanPanel::Run);
  connect(cancel_, &QPushButton::clicked, this, &PlanPanel::Cancel);
  connect(export_button, &QPushButton::clicked, this, &PlanPanel::ExportPlan);
  ShowProgressOn(job_, progress_);

  // The options scroll up and down, never sideways: the column is as wide as the form.
  auto* scroll = new QScrollArea;
  scroll->setObjectName("plan_options_scroll");
  scroll->setWidget(options_);
  scroll->setWidgetResizable(true);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setMinimumWidth(options_->minimumSizeHint().width() + scroll->verticalScrollBar()->sizeHint().width() +
                          2 * scroll->frameWidth());
  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  left_layout->addWidget(scroll, 1);
  left_layout->addWidget(visibility_);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(run_);
  buttons->addWidget(cancel_);
  left_layout->addLayout(buttons);
  left_layout->addWidget(progress_);
  left_layout->addWidget(status_);

  table_ = new QTableWidget(0, kColumns.size());
  table_->setObjectName("pose_table");
  table_->setHorizontalHeaderLabels(kColumns);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setSortingEnabled(true);
  table_->sortByColumn(0, Qt::AscendingOrder);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  connect(table_, &QTableWidget::cellChanged, this, &PlanPanel::OnCellEdited);
  connect(table_, &QTableWidget::currentCellChanged, this, [this](int row) {
    if (row >= 0 && table_->item(row, 0)) emit PoseSelected(table_->item(row, 0)->data(Qt::UserRole).toInt());
  });
  // Short texts, the rest in the tooltips: the row must fit the table's width at 1024×600.
  auto* delete_button = new QPushButton("Delete selected");
  delete_button->setToolTip("Delete the selected poses; the others are renumbered");
  auto* add_button = new QPushButton("Add pose");
  add_button->setToolTip("Add a pose at home, to edit in the table");
  connect(delete_button, &QPushButton::clicked, this, &PlanPanel::DeleteSelectedPoses);
  connect(add_button, &QPushButton::clicked, this, &PlanPanel::AddPose);
  auto* table_box = new QWidget;
  auto* table_layout = new QVBoxLayout(table_box);
  table_layout->addWidget(table_, 1);
  auto* table_buttons = new QHBoxLayout;
  table_buttons->addWidget(add_button);
  table_buttons->addWidget(delete_button);
  table_buttons->addStretch();
  table_buttons->addWidget(export_button);
  table_layout->addLayout(table_buttons);

  indices_ = charts::ObservabilityChart({});
  indices_chart_ = MakeChartView(indices_);
  legs_chart_ = MakeChartView(charts::LegReadingsChart(session_->NominalRobot(), {}));
  // One chart at a time, each the panel's whole width: side by side at
  // 1280 px their titles and legends were cut.
  auto* charts = new QTabWidget;
  charts->setObjectName("plan_charts");
  charts->addTab(indices_chart_, "Indices per iteration");
  charts->addTab(legs_chart_, "Leg readings per pose");
  auto* right = new QSplitter(Qt::Vertical);
  right->addWidget(charts);
  right->addWidget(table_box);
  right->setSizes({420, 400});
  auto* splitter = new QSplitter;
  splitter->addWidget(left);
  splitter->addWidget(right);
  splitter->setStretchFactor(1, 3);
  splitter->setSizes({330, 1050});
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(splitter);
  connect(job_, &BackgroundJob::Finished, this, [this] {
    run_->setEnabled(true);
    cancel_->setEnabled(false);
  });
  connect(visibility_, &VisibilityForm::Chosen, this, &PlanPanel::FillTable);
  connect(session_, &SessionState::Switched, this, &PlanPanel::ResetForSession);
  connect(session_, &SessionState::Changed, this, &PlanPanel::Refresh);
}

void PlanPanel::ResetForSession() {
  job_->Abandon();
  options_->Reset();
  visibility_->Reset();
  progress_->reset();
  outcome_from_job_ = false;
  SetOutcome(kIdleOutcome);
}

// The robot, the session's noise model (a points session's tracker: each
// pose's covariance and line of sight, workflow/session_plan_model.h) and the
// camera visibility chosen.
StatusOr<PlanningModel> PlanPanel::Model() const {
  StatusOr<std::optional<MeasurementConstraints>> visibility = visibility_->Constraints();
  if (!visibility.ok()) return visibility.status();
  StatusOr<PlanningModel> model =
      workflow::SessionPlanningModel(session_->Dir().toStdString(), session_->Config(), session_->NominalRobot());
  if (!model.ok()) return model.status();
  model->measurement = *visibility;
  return model;
}

void PlanPanel::SetOutcome(const QString& text) {
  outcome_ = InGuiTerms(text);
  status_->setText(Breakable(text));  // it may quote a long path
}

void PlanPanel::Run() {
  if (!session_->IsOpen()) return ShowError(this, "Plan", "Open or create a session first (File menu).");
  StatusOr<workflow::PlanSetup> options = options_->Options();
  if (!options.ok()) return ShowError(this, "Plan", QString::fromStdString(options.status().message()));
  StatusOr<PlanningModel> chosen = Model();
  if (!chosen.ok()) return ShowError(this, "Plan", QString::fromStdString(chosen.status().message()));
  const PlanningModel model = *chosen;
  indices_ = charts::ObservabilityChart({});
  ShowChart(indices_chart_, indices_);
  run_->setEnabled(false);
  cancel_->setEnabled(true);
  SetOutcome("planning…");
  plan_at_start_ = session_->Plan();
  QPointer<PlanPanel> self(this);
  job_->Start("planning", [this, self, model, setup = *options](const JobContext& context) -> GuiContinuation {
    // O1..O4 of every iteration as it is recorded. A queued call: the chart
    // is touched on the GUI thread only.
    const auto live = [self](const PlanIteration& step) {
      QMetaObject::invokeMethod(
          self, [self, step] { if (self && !self->job_->Abandoned()) self->PlotIteration(step); },
          Qt::QueuedConnection);
    };
    StatusOr<workflow::PlanOutcome> plan =
        workflow::RunPlan(model, setup, "", context, live);
    if (!plan.ok()) return [this, s = plan.status()] { Finish(s, {}); };
    return [this, outcome = std::move(*plan)] { Finish(Status::Ok(), outcome); };
  });
}

namespace {

// What the plan buys and how close to the best it is, under the indices line.
QString PredictionText(const workflow::PlanOutcome& outcome) {
  const workflow::PlanPrediction& p = outcome.prediction;
  QString text;
  if (p.valid) {
    const QString unit = QString::fromStdString(outcome.length_unit);
    text += QString("\nPredicted: parameter σ mean %1 (max %2), expected mean error %3; held-out FK error %4, %5.")
                .arg(FormatLength(p.mean_sigma, unit), FormatLength(p.max_sigma, unit),
                     FormatLength(p.mean_error, unit), FormatLength(p.heldout.position_rms, unit),
                     FormatAngle(p.heldout.orientation_rms_deg));
  }
  if (const auto& sigma = outcome.reflector_sigma) {
    const QString unit = QString::fromStdString(outcome.length_unit);
    text += QString("\nTracker: reflector σ %1 to %2 over the plan's poses%3.")
                .arg(FormatLength(sigma->first, unit), FormatLength(sigma->second, unit),
                     QString(outcome.line_of_sight ? ", every reflector in its line of sight" : ""));
  }
  if (const std::optional<PlanCertificate>& cert = outcome.certificate) {
    text += QString("\nS-efficiency ≥ %1, D-efficiency ≥ %2 on the candidates.")
                .arg(cert->s_efficiency, 0, 'f', 3)
                .arg(cert->d_efficiency, 0, 'f', 3);
  }
  return text;
}

}  // namespace

void PlanPanel::Finish(const Status& status, const workflow::PlanOutcome& outcome) {
  const PlanResult& result = outcome.plan;
  if (status.cancelled()) return SetOutcome("cancelled: the plan is unchanged.");
  if (!status.ok()) {
    const QString message = QString::fromStdString(WithOptionLabel(status, workflow::PlanSetupOptions()).message());
    SetOutcome("failed: " + message);
    return ShowError(this, "Plan", message + "\nTry more candidates, another candidate kind, or fewer poses.");
  }
  if (!ApplyPlan(result.poses, &plan_at_start_)) return;
  StatusOr<SessionLock> lock = SessionLock::Acquire(session_->Dir().toStdString(), LockWait::kBriefly);
  const Status history = lock.ok() ? workflow::WriteHistoryCsv(HistoryPath(*session_), result) : lock.status();
  if (!history.ok()) ShowError(this, "Plan", QString::fromStdString(history.message()));
  PlotHistory();  // the whole run, as plan_history.csv now holds it (SetPlan's refresh read the old one)
  outcome_from_job_ = true;
  outcome_plan_ = session_->Plan();
  SetOutcome(QString("done: %1 in %2%3; O1 %4 → %5, O3 %6 → %7")
                 .arg(FormatCount(result.iterations, "iteration"), FormatSeconds(result.seconds),
                      result.converged ? " (converged)" : "", FormatSignificant(result.initial.o1),
                      FormatSignificant(result.final.o1), FormatSignificant(result.initial.o3),
                      FormatSignificant(result.final.o3)) +
             PredictionText(outcome) + (plan_note_.isEmpty() ? QString() : "\n" + plan_note_));
}

bool PlanPanel::ApplyPlan(const std::vector<Vector6d>& plan, const std::vector<Vector6d>* seen) {
  const std::string dir = session_->Dir().toStdString();
  StatusOr<std::vector<workflow::ReadingsRow>> rows = workflow::ReadReadingsTable(dir);
  const std::vector<std::string> left =
      rows.ok()
          ? workflow::CapturesLeftByPlan(workflow::MakeReadingCheck(session_->NominalRobot(), session_->Config().noise),
                                         session_->Plan(), plan, *rows)
          : std::vector<std::string>{};
  plan_note_.clear();
  workflow::CaptureDisposal disposal = workflow::CaptureDisposal::kKeep;
  if (!left.empty()) {
    QStringList names;
    for (size_t k = 0; k < left.size() && k < 4; ++k) names << QString::fromStdString(left[k]);
    if (left.size() > 4) names << "…";
    const QString text = QString("The new plan leaves %1 without its pose (%2): taken at poses it does not have.")
                             .arg(FormatCount(static_cast<int>(left.size()), "recorded capture"), names.join(", "));
    // A points session's captures are legs.csv rows and the tracker's sets in
    // its points file, which hexcal does not archive or delete: kept, or no new plan.
    const int answer =
        session_->IsPointsSession()
            ? AskChoice(this, "Plan", text,
                        "Keep: they stay poses with readings and points, which the calibration uses; the new plan's "
                        "poses are recorded under new names.",
                        {"Keep captures", "Cancel"}, 0) == 0
                  ? 0
                  : -1
            : AskChoice(this, "Plan", text,
                        "Keep: they stay images with readings, which the calibration uses; the new plan's poses are "
                        "captured under new names.\nArchive: moved with their readings into the session's archive/ "
                        "folder, out of the calibration.\nDiscard: deleted with their readings.",
                        {"Keep captures", "Archive captures", "Discard captures", "Cancel"}, 0);
    if (answer < 0 || answer > 2) {
      SetOutcome("cancelled: the plan is unchanged.");
      return false;
    }
    disposal = static_cast<workflow::CaptureDisposal>(answer);
  }
  if (!ApplySessionEdit(this, "Plan", [&](bool overwrite) { return session_->SetPlan(plan, overwrite, seen); })) {
    SetOutcome("not saved: plan.csv was kept as another program wrote it.");
    return false;
  }
  if (left.empty()) return true;
  const QString count = FormatCount(static_cast<int>(left.size()), "capture");
  // After the plan is written: a plan not saved leaves the captures as they were.
  Status disposed = Status::Ok();
  if (disposal == workflow::CaptureDisposal::kKeep) {
    plan_note_ = QString("Kept %1 of the earlier plan.").arg(count);
  } else if (disposal == workflow::CaptureDisposal::kArchive) {
    StatusOr<std::string> archive = workflow::ArchiveCaptures(dir, left);
    disposed = archive.ok() ? Status::Ok() : archive.status();
    if (archive.ok())
      plan_note_ = QString("Moved %1 of the earlier plan to %2.")
                       .arg(count, session_->InSession(QString::fromStdString(*archive)));
  } else {
    disposed = workflow::DiscardCaptures(dir, left);
    plan_note_ = QString("Deleted %1 of the earlier plan.").arg(count);
  }
  session_->Reload();
  if (!disposed.ok()) {
    plan_note_.clear();
    ShowError(this, "Plan",
              "The plan is saved, but the captures were not " + QString(workflow::CaptureDisposalName(disposal)) +
                  "d: " + QString::fromStdString(disposed.message()));
  }
  if (!plan_note_.isEmpty()) SetOutcome(plan_note_);
  return true;
}

void PlanPanel::Cancel() {
  job_->Cancel();
  SetOutcome("cancelling…");
}

void PlanPanel::Refresh() {
  // The planner's outcome line lasts while plan.csv holds its plan.
  if (outcome_from_job_ && !job_->Running() && session_->Plan() != outcome_plan_) {
    outcome_from_job_ = false;
    SetOutcome(kIdleOutcome);
  }
  FillTable();
  PlotLegLengths();
  PlotHistory();
}

void PlanPanel::FillTable() {
  filling_ = true;
  table_->setSortingEnabled(false);
  const std::vector<Vector6d>& plan = session_->Plan();
  // Feasible under the robot and, when they load, the camera visibility chosen.
  const StatusOr<PlanningModel> chosen = Model();
  const PlanningModel model = chosen.ok() ? *chosen : PlanningModel{session_->NominalRobot(), {}, {}};
  table_->setRowCount(static_cast<int>(plan.size()));
  for (int j = 0; j < static_cast<int>(plan.size()); ++j) {
    QTableWidgetItem* index = SetEditable(new CoordinateItem(QString::number(j + 1)), false);
    index->setData(Qt::UserRole, j);
    table_->setItem(j, 0, index);
    for (int k = 0; k < 6; ++k) table_->setItem(j, 1 + k, NumberItem(plan[j][k], true));
    const LegReadings legs = InverseKinematics(model.robot, model.robot.PoseFromVector(plan[j]));
    for (int i = 0; i < kNumLegs; ++i) table_->setItem(j, 7 + i, NumberItem(legs[i], false));
    table_->setItem(j, 13, TableCell(model.IsFeasible(plan[j]) ? "yes" : "NO"));
  }
  table_->setSortingEnabled(true);
  filling_ = false;
}

void PlanPanel::OnCellEdited(int row, int column) {
  if (filling_ || column < 1 || column > 6) return;
  std::vector<Vector6d> plan = session_->Plan();
  const int index = table_->item(row, 0)->data(Qt::UserRole).toInt();
  bool number = false;
  const double value = table_->item(row, column)->text().toDouble(&number);
  if (!number || !std::isfinite(value)) {
    FillTable();  // the plan as it is
    return ShowError(this, "Plan", "A pose coordinate is a number: x, y, z in the robot unit, q1..q3 in degrees.");
  }
  plan[index][column - 1] = value;
  if (!ApplyPlan(plan)) FillTable();  // the table shows plan.csv again
}

void PlanPanel::DeleteSelectedPoses() {
  std::set<int> doomed;
  for (const QModelIndex& row : table_->selectionModel()->selectedRows())
    doomed.insert(table_->item(row.row(), 0)->data(Qt::UserRole).toInt());
  if (doomed.empty()) return ShowError(this, "Plan", "Select the rows of the poses to delete first.");
  std::vector<Vector6d> plan;
  for (int j = 0; j < static_cast<int>(session_->Plan().size()); ++j)
    if (!doomed.count(j)) plan.push_back(session_->Plan()[j]);
  ApplyPlan(plan);
}

void PlanPanel::AddPose() {
  std::vector<Vector6d> plan = session_->Plan();
  plan.push_back(WorkspaceCentre(session_->NominalRobot()));
  ApplyPlan(plan);
}

void PlanPanel::ExportPlan() {
  if (session_->Plan().empty()) return ShowError(this, "Export plan", "There is no plan yet: run the planner first.");
  const QString file = QFileDialog::getSaveFileName(this, "Export plan", "plan.csv", "CSV (*.csv)");
  if (file.isEmpty()) return;
  if (Status s = workflow::WritePlanCsv(file.toStdString(), PlanningModel{session_->NominalRobot(), {}, {}},
                                              session_->Plan()); !s.ok())
    ShowError(this, "Export plan", QString::fromStdString(s.message()));
}

void PlanPanel::PlotLegLengths() {
  ShowChart(legs_chart_, charts::LegReadingsChart(session_->NominalRobot(), session_->Plan()));
}

void PlanPanel::PlotIteration(const PlanIteration& step) {
  // The first step seen makes the chart, whatever its number: appended to the
  // empty chart of Run(), the points were drawn against its 0..1 axis.
  if (step.iteration == 0 || indices_.series.empty() || indices_.series.front().points.empty()) {
    indices_ = charts::ObservabilityChart({step});
    return ShowChart(indices_chart_, indices_);
  }
  const std::vector<double> values = charts::IndexValues(step.indices);
  for (int k = 0; k < 4; ++k)
    charts::AppendPoint(indices_chart_->chart(), &indices_, k, {static_cast<double>(step.iteration), values[k]});
}

void PlanPanel::PlotHistory() {
  if (job_->Running()) return;  // the live plot is on
  std::vector<PlanIteration> iterations;
  StatusOr<CsvTable> history = ReadCsv(HistoryPath(*session_));
  for (size_t r = 0; history.ok() && r < history->rows.size(); ++r) {
    StatusOr<double> iteration = NumberAt(*history, r, 0);
    if (!iteration.ok()) continue;
    double o[4];  // a missing index is NaN: not drawn
    for (int k = 0; k < 4; ++k) {
      StatusOr<double> value = NumberAt(*history, r, 1 + k);
      o[k] = value.ok() ? *value : std::nan("");
    }
    iterations.push_back({static_cast<int>(*iteration), {o[0], o[1], o[2], o[3]}});
  }
  indices_ = charts::ObservabilityChart(iterations);
  if (!history.ok()) indices_.title = "Indices per iteration: run the planner to see them";
  ShowChart(indices_chart_, indices_);
}

}  // namespace hexcal::ui

#include "ui/calibrate_panel.h"

#include <QChartView>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <utility>

#include "charts/figures.h"
#include "core/inverse_kinematics.h"
#include "core/measurements.h"
#include "core/robot_io.h"
#include "report/calibration_verdict.h"
#include "session/results_files.h"
#include "session/session_results.h"
#include "ui/background_job.h"
#include "ui/charts.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/quantity_format.h"
#include "ui/run_log.h"
#include "ui/text_wrap.h"
#include "ui/verdict_view.h"
#include "workflow/session_calibrate.h"

namespace hexcal::ui {
namespace {

// Sorts by the number it holds, whatever its text.
class NumberItem : public QTableWidgetItem {
 public:
  NumberItem(const QString& text, double value) : QTableWidgetItem(text) { setData(Qt::UserRole, value); }
  bool operator<(const QTableWidgetItem& other) const override {
    return data(Qt::UserRole).toDouble() < other.data(Qt::UserRole).toDouble();
  }
};

// |change|/σ as "yes, 110σ": far above 3 the parameter was identified and
// differs from nominal, which is no alarm (docs/calibration.md, "Verdict").
QTableWidgetItem* IdentifiedItem(const workflow::ParameterEstimate& p) {
  if (!p.sigma || *p.sigma <= 0) return new NumberItem("—", -1);
  const double ratio = std::abs(p.estimate - p.nominal) / *p.sigma;
  return new NumberItem(QString("%1, %2σ").arg(ratio > 3 ? "yes" : "no", FormatSignificant(ratio)), ratio);
}

}  // namespace

CalibratePanel::CalibratePanel(SessionState* session, QWidget* parent)
    : QWidget(parent), session_(session), job_(new BackgroundJob(this)) {
  run_ = new QPushButton("Calibrate session");
  run_->setObjectName("calibrate_run");
  run_->setToolTip(
      "Measure the images not yet measured, register camera and target with the nominal robot, "
      "calibrate on the images not held out, validate on the held-out ones; writes results/.");
  cancel_ = new QPushButton("Cancel");
  cancel_->setEnabled(false);
  progress_ = new QProgressBar;
  status_ = new QLabel;
  status_->setTextFormat(Qt::PlainText);  // file names are shown as they are, never as HTML
  status_->setWordWrap(true);
  status_->setObjectName("calibrate_status");
  summary_ = new QLabel;
  summary_->setWordWrap(true);
  summary_->setObjectName("calibrate_summary");
  summary_->setTextFormat(Qt::RichText);
  parameters_ = new QTableWidget(0, 7);
  parameters_->setObjectName("parameter_table");
  verdict_ = new VerdictView;
  parameters_->setHorizontalHeaderLabels({"leg", "parameter", "nominal", "calibrated", "change", "σ", "identified"});
  // |change|/σ far above 3 says the parameter was identified, not that something is wrong.
  parameters_->horizontalHeaderItem(6)->setToolTip(
      "|change|/σ: well above 3 (change ≫ σ) means the calibration identified this parameter and found it "
      "differs from nominal. Expected, not an alarm.");
  parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  for (int narrow : {0, 1}) parameters_->horizontalHeader()->setSectionResizeMode(narrow, QHeaderView::ResizeToContents);
  parameters_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  parameters_->setSortingEnabled(true);
  parameters_->sortByColumn(0, Qt::AscendingOrder);
  residuals_ = MakeChartView(charts::CalibrationResidualsChart(session_->NominalRobot(), session_->NominalRobot(), {}));
  connect(run_, &QPushButton::clicked, this, &CalibratePanel::Run);
  connect(cancel_, &QPushButton::clicked, this, [this] {
    job_->Cancel();
    SetOutcome("cancelling…");
  });
  ShowProgressOn(job_, progress_);

  run_log_ = new RunLog;
  ArrangeWidgets();
  connect(job_, &BackgroundJob::Finished, this, [this] {
    run_->setEnabled(true);
    cancel_->setEnabled(false);
  });
  connect(session_, &SessionState::Switched, this, &CalibratePanel::ResetForSession);
  connect(session_, &SessionState::Changed, this, &CalibratePanel::Refresh);
}

// The summary once (counts, closure, the fit from pixels), the verdict, and
// the table and the chart as tabs, so that the table keeps a usable height
// at 1024×600 whatever the verdict says; the raw lines fold into the run log.
void CalibratePanel::ArrangeWidgets() {
  auto* controls = new QHBoxLayout;
  controls->addWidget(run_);
  controls->addWidget(cancel_);
  controls->addWidget(progress_, 1);
  controls->addStretch();
  auto* results = new QTabWidget;
  results->setObjectName("calibrate_tabs");
  results->addTab(parameters_, "Parameters");
  results->addTab(residuals_, "Leg residuals");
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(controls);
  layout->addWidget(status_);
  layout->addWidget(run_log_);
  layout->addWidget(summary_);
  layout->addWidget(verdict_);
  layout->addWidget(results, 1);
}

void CalibratePanel::ResetForSession() {
  job_->Abandon();
  progress_->reset();
  run_log_->SetText({});
  outcome_from_job_ = false;
  SetOutcome({});
}

void CalibratePanel::SetOutcome(const QString& text) {
  outcome_ = InGuiTerms(text);            // the workflow's errors name the CLI's flags
  status_->setText(Breakable(outcome_));  // a stale note may quote a long path
}

void CalibratePanel::Run() {
  if (!session_->IsOpen()) return ShowError(this, "Calibrate", "Open or create a session first (File menu).");
  session_->Reload();  // the checks below on the files as they are now, whatever a watcher missed
  if (!session_->LegsError().isEmpty())
    return ShowError(this, "Calibrate", "legs.csv: " + session_->LegsError() + "\nFix it in the Measure step.");
  // A points session has neither: its poses come from the points file.
  if (!session_->IsPointsSession() && (!session_->SessionCamera() || !session_->SessionTarget()))
    return ShowError(this, "Calibrate", "The session's camera or target does not load: fix session.yaml.");
  const std::string dir = session_->Dir().toStdString();
  run_->setEnabled(false);
  cancel_->setEnabled(true);
  SetOutcome("calibrating…");
  job_->Start("calibrating", [=](const JobContext& context) -> GuiContinuation {
    // The session calibration measures the images not yet in camera_poses.csv
    // (keeping the rows already there), as `hexcal calibrate --session` does.
    context.progress(0, 0);  // a busy bar until the first report
    StatusOr<workflow::CalibrationReport> report =
        workflow::CalibrateSession({dir}, context);
    const Status status = report.ok() ? Status::Ok() : report.status();
    return [this, status] { Finish(status); };
  });
}

void CalibratePanel::Finish(const Status& status) {
  outcome_from_job_ = true;
  outcome_basis_ = QString();  // noted by the refresh the reload below brings
  // One line here: the figures are in the summary below, the printed lines in the run log.
  if (status.cancelled()) {
    SetOutcome("cancelled: results/ is unchanged.");
  } else if (!status.ok()) {
    SetOutcome("failed: " + QString::fromStdString(status.message()).trimmed() + " results/ is unchanged.");
    ShowError(this, "Calibrate",
              QString::fromStdString(status.message()).trimmed() +
                  (session_->IsPointsSession()
                       ? "\nCheck the Measure step: enough poses whose points fit, and their readings."
                       : "\nCheck the Measure step: enough images with an ok target pose and their readings."));
  } else {
    SetOutcome("done: results/ written; the run's lines are in the run log.");
  }
  session_->Reload();
}

void CalibratePanel::Refresh() {
  // A run's outcome line lasts while the results are as the run left them:
  // the first refresh after it notes the step's state, a later one that finds
  // it changed (a reading edited, an image added) shows the idle line again.
  if (!job_->Running() && outcome_from_job_) {
    const QString now =
        QString::number(static_cast<int>(session_->State(Step::kCalibrate))) + session_->Why(Step::kCalibrate);
    if (outcome_basis_.isNull()) {
      outcome_basis_ = now;
    } else if (now != outcome_basis_) {
      outcome_from_job_ = false;
      outcome_.clear();
    }
  }
  const bool points = session_->IsPointsSession();
  run_->setToolTip(points ? "Fit each pose's points to the reflectors, register the tracker and the reflectors with "
                            "the nominal robot, calibrate on the poses not held out, validate on the held-out ones; "
                            "writes results/."
                          : "Measure the images not yet measured, register camera and target with the nominal robot, "
                            "calibrate on the images not held out, validate on the held-out ones; writes results/.");
  // Between runs the line under the buttons says what the results are.
  if (!job_->Running() && (outcome_.isEmpty() || outcome_ == idle_)) {
    const StepState state = session_->State(Step::kCalibrate);
    idle_ = state == StepState::kDone     ? "Results up to date with the session's files."
            : state == StepState::kStale  ? "Results stale: " + session_->ResultsNote()
            : state == StepState::kBroken ? "Results do not load: " + session_->InSession(session_->ResultsNote())
            : points                      ? "Record the points file and the readings of its poses (Measure), then "
                                            "calibrate."
                                          : "Record images and readings (Acquire, Measure), then calibrate.";
    idle_ = InGuiTerms(idle_);  // as SetOutcome shows it, to compare with
    SetOutcome(idle_);
  }
  parameters_->setSortingEnabled(false);
  parameters_->setRowCount(0);
  // The headers in this session's unit, with results or without (another
  // session's unit stayed until its results loaded).
  SetUnitHeaders(LengthUnitName(session_->NominalRobot().length_unit));
  summary_->clear();
  verdict_->Clear();
  run_log_->SetText({});
  const StatusOr<workflow::SessionResults>& loaded = session_->Results();
  if (!session_->IsOpen() || !loaded.ok()) {
    summary_->setText(session_->IsOpen() ? QString::fromStdString(loaded.status().message()).toHtmlEscaped() : "");
    PlotResiduals();
    return;
  }
  const workflow::CalibrationReport& report = loaded->report;
  const workflow::RegistrationSummary& reg = report.registration;
  const QString unit = QString::fromStdString(report.length_unit);
  // The counts and the closure once; the rest of what the CLI prints (the
  // fit from pixels, the camera-frame residuals, outliers) in the run log.
  // A points session's report counts poses measured by the tracker.
  const bool tracker = report.instrument == Instrument::kPoints;
  summary_->setText(QString("%1: %2 for calibration, %3 held out, %4 without a usable %5. "
                            "Closure (%6 vs robot) RMS: nominal robot %7, %8; calibrated %9, %10.")
                        .arg(FormatCount(report.images, MeasurementNoun(report.instrument)))
                        .arg(report.calibration_images)
                        .arg(report.held_out_images)
                        .arg(report.unusable_images)
                        .arg(tracker ? "fit of their points" : "target pose", tracker ? "tracker" : "camera")
                        .arg(FormatLength(reg.position_rms, unit).toHtmlEscaped(), FormatAngle(reg.angle_rms_deg),
                             FormatLength(report.closure_position_rms, unit).toHtmlEscaped(),
                             FormatAngle(report.closure_angle_rms_deg)) +
                    (session_->ResultsNote().isEmpty() || outcome_ == idle_  // the line above says it
                         ? QString()
                         : "<br><b>Stale:</b> " + Breakable(InGuiTerms(session_->ResultsNote())).toHtmlEscaped()));
  run_log_->SetText(QString::fromStdString(workflow::FormatCalibrationSummary(report)).trimmed());
  verdict_->Show(workflow::MakeVerdict(report),
                 session_->State(Step::kCalibrate) == StepState::kStale ? session_->ResultsNote() : QString());
  FillParameterTable(report.parameters, QString::fromStdString(report.length_unit));
  PlotResiduals();
}

void CalibratePanel::SetUnitHeaders(const QString& unit) {
  for (const auto& [column, name] : {std::pair<int, QString>{2, "nominal"}, {3, "calibrated"}, {4, "change"}, {5, "σ"}})
    parameters_->horizontalHeaderItem(column)->setText(name + " (" + unit + ")");
}

void CalibratePanel::FillParameterTable(const std::vector<workflow::ParameterEstimate>& rows, const QString& unit) {
  SetUnitHeaders(unit);
  const auto cell = [](const QVariant& v) {
    auto* item = new QTableWidgetItem;
    item->setData(Qt::DisplayRole, v);
    return item;
  };
  parameters_->setRowCount(static_cast<int>(rows.size()));
  for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
    const workflow::ParameterEstimate& p = rows[r];
    const double change = p.estimate - p.nominal;
    parameters_->setItem(r, 0, cell(p.leg));
    parameters_->setItem(r, 1, cell(QString::fromStdString(p.name)));
    // Values to the robot unit's 1e-4, changes and σ to three digits (ui/quantity_format.h).
    parameters_->setItem(r, 2, new NumberItem(FormatCoordinate(p.nominal), p.nominal));
    parameters_->setItem(r, 3, new NumberItem(FormatCoordinate(p.estimate), p.estimate));
    parameters_->setItem(r, 4, new NumberItem(FormatSignificant(change), change));
    parameters_->setItem(r, 5, p.sigma ? new NumberItem(FormatSignificant(*p.sigma), *p.sigma) : cell("—"));
    parameters_->setItem(r, 6, IdentifiedItem(p));
  }
  parameters_->setSortingEnabled(true);
}

// Only from results/ that loaded whole: a half-written or mixed results/ shows no chart.
void CalibratePanel::PlotResiduals() {
  if (!session_->Results().ok())
    return ShowChart(residuals_, charts::CalibrationResidualsChart(session_->NominalRobot(), session_->NominalRobot(), {}));
  StatusOr<std::vector<Measurement>> rows =
      LoadMeasurements(workflow::ResultsFile(session_->Paths().dir, workflow::kUsedMeasurements));
  StatusOr<Robot> calibrated = LoadRobot(workflow::ResultsFile(session_->Paths().dir, workflow::kCalibratedRobot));
  const Robot& robot = session_->NominalRobot();
  if (!rows.ok() || !calibrated.ok()) return ShowChart(residuals_, charts::CalibrationResidualsChart(robot, robot, {}));
  ShowChart(residuals_, charts::CalibrationResidualsChart(robot, *calibrated, *rows));
}

}  // namespace hexcal::ui

#include "ui/validate_panel.h"

#include <QChartView>
#include <QFile>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <array>
#include <cmath>

#include "charts/figures.h"
#include "core/atomic_file.h"
#include "report/calibration_verdict.h"
#include "report/session_report.h"
#include "session/results_files.h"
#include "session/session_results.h"
#include "ui/charts.h"
#include "ui/error_dialog.h"
#include "ui/quantity_format.h"
#include "ui/study_view.h"
#include "ui/text_wrap.h"
#include "ui/verdict_view.h"

namespace hexcal::ui {
namespace {

// A missing figure (FK did not converge) draws no bar.
double ValueOrNan(const std::optional<double>& value) { return value.value_or(std::nan("")); }

}  // namespace

ValidatePanel::ValidatePanel(SessionState* session, QWidget* parent) : QWidget(parent), session_(session) {
  status_ = new QLabel;
  status_->setTextFormat(Qt::PlainText);  // file names are shown as they are, never as HTML
  status_->setWordWrap(true);
  status_->setObjectName("validate_status");
  verdict_ = new VerdictView;
  summary_ = new QTableWidget(4, 2);
  summary_->setObjectName("validation_summary");
  summary_->setHorizontalHeaderLabels({"nominal robot (before)", "calibrated robot (after)"});
  summary_->setVerticalHeaderLabels({"position RMS", "position max", "orientation RMS", "orientation max"});
  summary_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  summary_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  // Its four rows exactly, each one line high: the charts below get the rest.
  summary_->verticalHeader()->setDefaultSectionSize(summary_->fontMetrics().height() + 8);
  summary_->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  summary_->setFixedHeight(4 * summary_->verticalHeader()->defaultSectionSize() +
                           summary_->horizontalHeader()->sizeHint().height() + 2 * summary_->frameWidth());
  position_chart_ = MakeChartView(charts::ValidationPerImageChart({}, charts::ValidationQuantity::kPosition, ""));
  orientation_chart_ = MakeChartView(charts::ValidationPerImageChart({}, charts::ValidationQuantity::kOrientation, ""));
  auto* export_robot = new QPushButton("Export calibrated robot…");
  export_robot->setObjectName("export_robot");
  auto* export_report = new QPushButton("Export HTML report…");
  export_report->setObjectName("export_report");
  connect(export_robot, &QPushButton::clicked, this, [this] { ExportCalibratedRobot(); });
  connect(export_report, &QPushButton::clicked, this, [this] { ExportHtmlReport(); });
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(export_robot);
  buttons->addWidget(export_report);
  buttons->addStretch();
  auto* charts = new QHBoxLayout;
  charts->addWidget(position_chart_);
  charts->addWidget(orientation_chart_);
  auto* validation = new QWidget;
  auto* validation_layout = new QVBoxLayout(validation);
  validation_layout->addWidget(verdict_);
  validation_layout->addWidget(status_);
  validation_layout->addWidget(summary_);
  validation_layout->addLayout(charts, 1);
  validation_layout->addStretch(0);  // the room of the figures when there are none
  study_ = new StudyView(session_);
  tabs_ = new QTabWidget;
  tabs_->addTab(validation, "Held-out validation");
  tabs_->addTab(study_, "Section 8 study");
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(tabs_, 1);
  layout->addLayout(buttons);
  connect(session_, &SessionState::Changed, this, &ValidatePanel::Refresh);
}

void ValidatePanel::ShowStudyTab() { tabs_->setCurrentWidget(study_); }

void ValidatePanel::ShowValidationTab() { tabs_->setCurrentIndex(0); }

void ValidatePanel::Refresh() {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 2; ++c) summary_->setItem(r, c, new QTableWidgetItem("—"));
  const StatusOr<workflow::SessionResults>& results = session_->Results();
  StatusOr<workflow::CalibrationReport> report =
      results.ok() ? StatusOr<workflow::CalibrationReport>(results->report) : results.status();
  const std::string row_noun = session_->RowNoun().toStdString();
  ShowChart(position_chart_, charts::ValidationPerImageChart({}, charts::ValidationQuantity::kPosition, "", row_noun));
  ShowChart(orientation_chart_,
            charts::ValidationPerImageChart({}, charts::ValidationQuantity::kOrientation, "", row_noun));
  verdict_->Clear();
  // Figures only when there are some: empty axes and a table of dashes said nothing.
  const bool validated = report.ok() && report->validation.has_value();
  for (QWidget* figures : {static_cast<QWidget*>(summary_), static_cast<QWidget*>(position_chart_),
                           static_cast<QWidget*>(orientation_chart_)})
    figures->setVisible(validated);
  if (!report.ok()) return status_->setText(Breakable(QString::fromStdString(report.status().message())));
  // Never a verdict without its stale mark (issue 40): the figures below are of the same results.
  verdict_->Show(workflow::MakeVerdict(*report),
                 session_->State(Step::kCalibrate) == StepState::kStale ? session_->ResultsNote() : QString());
  // A points session's rows are poses, measured by the tracker.
  const QString noun = MeasurementNoun(report->instrument);
  if (!report->validation) {
    status_->setText(QString("No %1 was held out (holdout column of legs.csv), so there is nothing to validate on. "
                             "Mark some %1s with holdout 1 in the Measure step and calibrate again.")
                         .arg(noun));
    return;
  }
  ShowValidation(*report->validation, QString::fromStdString(report->length_unit), noun);
}

void ValidatePanel::ShowValidation(const workflow::ValidationSummary& validation, const QString& unit,
                                   const QString& noun) {
  status_->setText(QString("%1 held-out %2s: forward kinematics from their readings against the %3's pose, "
                           "lengths in %4. Rows where FK did not converge: before %5, after %6.")
                       .arg(validation.rows)
                       .arg(noun, noun == "pose" ? "tracker" : "camera", unit)
                       .arg(validation.before.failed)
                       .arg(validation.after.failed));
  const auto figures = [](const workflow::PoseErrorStats& s) {
    return std::array<double, 4>{s.position_rms, s.position_max, s.orientation_rms, s.orientation_max};
  };
  const std::array<double, 4> before = figures(validation.before), after = figures(validation.after);
  for (int r = 0; r < 4; ++r) {
    const auto figure = [&](double value) { return r < 2 ? FormatLength(value, unit) : FormatAngle(value); };
    summary_->setItem(r, 0, new QTableWidgetItem(figure(before[r])));
    summary_->setItem(r, 1, new QTableWidgetItem(figure(after[r])));
  }
  std::vector<charts::ImageValidation> images;
  for (const workflow::HeldOutImage& row : validation.per_image) {
    // The number in the image's (pose's) name fits under a bar.
    const QString name = QString::fromStdString(row.image).section('.', 0, 0);
    const QRegularExpressionMatch number = QRegularExpression("(\\d+)$").match(name);
    images.push_back({(number.hasMatch() ? number.captured(1) : name).toStdString(),
                      {ValueOrNan(row.position_before), ValueOrNan(row.position_after),
                       ValueOrNan(row.orientation_before), ValueOrNan(row.orientation_after)}});
  }
  const std::string length_unit = unit.toStdString();
  ShowChart(position_chart_, charts::ValidationPerImageChart(images, charts::ValidationQuantity::kPosition,
                                                             length_unit, noun.toStdString()));
  ShowChart(orientation_chart_, charts::ValidationPerImageChart(images, charts::ValidationQuantity::kOrientation,
                                                                length_unit, noun.toStdString()));
}

// The session read again (what a watcher missed is seen), then: results
// that do not load are refused, stale ones used only when the operator says
// so with the reason in front of them (issue 40).
bool ValidatePanel::ResultsUsable(const QString& what) {
  session_->Reload();
  switch (session_->State(Step::kCalibrate)) {
    case StepState::kDone:
      return true;
    case StepState::kStale:
      return ConfirmStale(this, what,
                          "The results are stale: " + session_->InSession(session_->ResultsNote()) +
                              "\nThey were computed from files that have changed since.");
    case StepState::kBroken:
      ShowError(this, what, "The results do not load: " + session_->InSession(session_->ResultsNote()));
      return false;
    case StepState::kTodo:
      break;
  }
  ShowError(this, what, "No results yet: run the Calibrate step.");
  return false;
}

void ValidatePanel::ExportCalibratedRobot(const QString& chosen) {
  if (!session_->IsOpen()) return ShowError(this, "Export robot", "Open a session first (File menu).");
  const QString source =
      QString::fromStdString(workflow::ResultsFile(session_->Paths().dir, workflow::kCalibratedRobot));
  if (!ResultsUsable("Export robot")) return;
  if (!QFile::exists(source))
    return ShowError(this, "Export robot", "No calibrated robot yet: run the Calibrate step.");
  const QString path = chosen.isEmpty() ? QFileDialog::getSaveFileName(this, "Export calibrated robot",
                                                                       workflow::kCalibratedRobot, "YAML (*.yaml)")
                                        : chosen;
  if (path.isEmpty()) return;
  // Written whole or not at all: a copy cut short would leave a robot file that loads wrong.
  StatusOr<std::string> robot = ReadFileToString(source.toStdString(), kMaxYamlBytes);
  const Status written = robot.ok() ? WriteFileAtomically(path.toStdString(), *robot) : robot.status();
  if (!written.ok()) ShowError(this, "Export robot", session_->InSession(QString::fromStdString(written.message())));
}

void ValidatePanel::ExportHtmlReport(const QString& chosen) {
  if (!session_->IsOpen()) return ShowError(this, "Export report", "Open a session first (File menu).");
  if (!ResultsUsable("Export report")) return;
  const QString path = chosen.isEmpty()
                           ? QFileDialog::getSaveFileName(this, "Export HTML report", workflow::kHtmlReport,
                                                          "HTML (*.html)")
                           : chosen;
  if (path.isEmpty()) return;
  // The same step as `hexcal report`, so the page is the CLI's.
  const StatusOr<std::string> written =
      workflow::WriteSessionReport({session_->Dir().toStdString(), path.toStdString(), /*force=*/true});
  if (!written.ok())
    ShowError(this, "Export report", QString::fromStdString(written.status().message()));
}

}  // namespace hexcal::ui

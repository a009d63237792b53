#include "ui/study_view.h"

#include <QChartView>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "charts/figures.h"
#include "session/session_study.h"
#include "ui/background_job.h"
#include "ui/charts.h"
#include "ui/error_dialog.h"
#include "ui/quantity_format.h"
#include "ui/text_wrap.h"
#include "workflow/study_options.h"

namespace hexcal::ui {
namespace {

// Table 5's rows: the held-out errors first, what the study is for.
constexpr SubsetMetric kRows[] = {SubsetMetric::kHeldOutPosition,
                                  SubsetMetric::kHeldOutOrientation,
                                  SubsetMetric::kO1,
                                  SubsetMetric::kO2,
                                  SubsetMetric::kO3,
                                  SubsetMetric::kO4};

int ChartIndex(SubsetMetric metric) { return static_cast<int>(metric); }  // kSubsetMetrics order

// Three significant digits, as every error in the GUI (ui/quantity_format.h);
// the unit is in the row's header, so that a p5 – p95 range fits its cell.
QString MetricText(double value) { return FormatSignificant(value); }

QString RowHeader(SubsetMetric metric, const QString& unit) {
  switch (metric) {
    case SubsetMetric::kHeldOutPosition:
      return "held-out position (" + unit + ")";
    case SubsetMetric::kHeldOutOrientation:
      return "held-out orientation (°)";
    default:
      return SubsetMetricName(metric);
  }
}

charts::ChartSpec EmptyChart(SubsetMetric metric, const std::string& length_unit) {
  return charts::StudyMetricChart(metric, {}, std::nan(""), workflow::StudyRequest{}.study.select, length_unit);
}

// Two charts side by side, one tab.
QWidget* ChartPair(QtCharts::QChartView* left, QtCharts::QChartView* right) {
  auto* pair = new QWidget;
  auto* layout = new QHBoxLayout(pair);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(left);
  layout->addWidget(right);
  return pair;
}

}  // namespace

StudyView::StudyView(SessionState* session, QWidget* parent)
    : QWidget(parent), session_(session), job_(new BackgroundJob(this)) {
  auto* form = new QFormLayout;
  options_ = AddOptionRows(form, workflow::StudyOptions(), workflow::StudyRequest{});
  run_ = new QPushButton("Run study");
  run_->setObjectName("study_run");
  run_->setToolTip(
      "IOOPS's subset of the session's measured poses against random subsets of the same size, each "
      "calibrated and validated on the poses it leaves out (hexcal study); kept in the session's study/.");
  cancel_ = new QPushButton("Cancel");
  cancel_->setEnabled(false);
  progress_ = new QProgressBar;
  outcome_label_ = new QLabel;
  outcome_label_->setTextFormat(Qt::PlainText);  // file names as they are
  outcome_label_->setWordWrap(true);
  rank_ = new QLabel;
  rank_->setObjectName("study_rank");
  rank_->setTextFormat(Qt::RichText);
  rank_->setWordWrap(true);
  about_ = new QLabel;
  about_->setTextFormat(Qt::PlainText);
  about_->setWordWrap(true);
  table_ = new QTableWidget(6, 5);
  table_->setObjectName("study_table");
  // Two-line headers: the five columns then fit the panel at 1024×600.
  table_->setHorizontalHeaderLabels({"selected", "random\nmean", "random\nmedian", "random\np5 – p95", "beats"});
  table_->horizontalHeaderItem(4)->setToolTip(
      "The percentage of random subsets the selected one does better than: a lower held-out error, a higher "
      "index (ties count half).");
  for (int r = 0; r < 6; ++r) table_->setVerticalHeaderItem(r, new QTableWidgetItem(RowHeader(kRows[r], "cm")));
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  table_->verticalHeader()->setDefaultSectionSize(22);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (SubsetMetric metric : kSubsetMetrics) charts_[ChartIndex(metric)] = MakeChartView(EmptyChart(metric, "cm"));
  // Table 5 and the figures as tabs: one above the other left the charts
  // no room at 1024×600.
  auto* figures = new QTabWidget;
  figures->setObjectName("study_tabs");
  auto* table_tab = new QWidget;
  auto* table_layout = new QVBoxLayout(table_tab);
  table_layout->addWidget(table_);  // the tab's height: at 1024×600 it also scrolls sideways
  figures->addTab(table_tab, "Table 5");
  figures->addTab(ChartPair(charts_[4], charts_[5]), "Fig. 19: held-out errors");
  figures->addTab(ChartPair(charts_[0], charts_[1]), "Fig. 18: O1, O2");
  figures->addTab(ChartPair(charts_[2], charts_[3]), "Fig. 18: O3, O4");

  auto* buttons = new QHBoxLayout;
  buttons->addWidget(run_);
  buttons->addWidget(cancel_);
  auto* left = new QVBoxLayout;
  left->addLayout(form);
  left->addLayout(buttons);
  left->addWidget(progress_);
  left->addWidget(outcome_label_);
  left->addStretch();
  auto* left_widget = new QWidget;
  left_widget->setLayout(left);
  left_widget->setFixedWidth(260);
  auto* right = new QVBoxLayout;
  right->addWidget(rank_);
  right->addWidget(about_);
  right->addWidget(figures, 1);
  auto* layout = new QHBoxLayout(this);
  layout->addWidget(left_widget);
  layout->addLayout(right, 1);

  connect(run_, &QPushButton::clicked, this, &StudyView::Run);
  connect(cancel_, &QPushButton::clicked, this, [this] {
    job_->Cancel();
    SetOutcome("cancelling…");
  });
  ShowProgressOn(job_, progress_);
  connect(job_, &BackgroundJob::Finished, this, [this] {
    run_->setEnabled(true);
    cancel_->setEnabled(false);
  });
  connect(session_, &SessionState::Switched, this, &StudyView::ResetForSession);
  connect(session_, &SessionState::Changed, this, &StudyView::Refresh);
}

void StudyView::SetOption(const std::string& key, const std::string& text) { options_.at(key).set_text(text); }

void StudyView::SetOutcome(const QString& text) {
  outcome_ = text;
  outcome_label_->setText(Breakable(text));  // it quotes the session's folder
}

// A session switch: the old session's job and texts go, the options back to their defaults.
void StudyView::ResetForSession() {
  job_->Abandon();
  progress_->reset();
  SetOutcome({});
  const workflow::StudyRequest defaults;
  for (const OptionSpec<workflow::StudyRequest>& spec : workflow::StudyOptions())
    options_.at(spec.key).set_text(OptionText(spec, defaults));
}

void StudyView::Run() {
  if (!session_->IsOpen()) return ShowError(this, "Section 8 study", "Open a session first (File menu).");
  StatusOr<workflow::StudyRequest> request = ReadOptionRows(workflow::StudyOptions(), options_);
  if (!request.ok()) return ShowError(this, "Section 8 study", QString::fromStdString(request.status().message()));
  request->session = session_->Dir().toStdString();
  request->save = false;  // SaveSessionStudy draws with Qt: on this thread, in Finish
  request->wait = LockWait::kBriefly;
  run_->setEnabled(false);
  cancel_->setEnabled(true);
  SetOutcome("running the study…");
  job_->Start("study", [this, request = *request](const JobContext& context) -> GuiContinuation {
    context.progress(0, 0);  // a busy bar until the subsets start
    auto outcome = std::make_shared<StatusOr<workflow::StudyOutcome>>(workflow::RunStudy(request, context));
    return [this, outcome] { Finish(outcome); };
  });
}

void StudyView::Finish(const std::shared_ptr<StatusOr<workflow::StudyOutcome>>& outcome) {
  if (!outcome->ok()) {
    if (outcome->status().cancelled()) return SetOutcome("cancelled: study/ is unchanged.");
    SetOutcome("failed.");
    const Status said = WithOptionLabel(outcome->status(), workflow::StudyOptions());
    return ShowError(this, "Section 8 study", QString::fromStdString(said.message()));
  }
  workflow::StudyOutcome& done = **outcome;
  if (Status saved = workflow::SaveSessionStudy(&done, LockWait::kBriefly); !saved.ok()) {
    SetOutcome("done, but not kept.");
    return ShowError(this, "Section 8 study", QString::fromStdString(saved.message()));
  }
  SetOutcome(QString("done in %1 on %2; kept in %3.")
                 .arg(FormatSeconds(done.seconds), FormatCount(done.threads, "thread"))
                 .arg(session_->InSession(QString::fromStdString(done.saved) + "/")));  // "study/"
  session_->Reload();  // shows what study/ now holds
}

void StudyView::Refresh() {
  if (!session_->IsOpen()) return ShowEmpty({});
  const StatusOr<workflow::SessionStudy>& study = session_->Study();
  if (!study.ok()) return ShowEmpty(QString::fromStdString(study.status().message()));
  ShowStudy(*study);
}

// The session's length unit before a study gives one (the robot's).
void StudyView::ShowEmpty(const QString& why) {
  const std::string unit = LengthUnitName(session_->NominalRobot().length_unit);
  rank_->setText(why.toHtmlEscaped());
  about_->clear();
  for (int r = 0; r < 6; ++r) {
    table_->verticalHeaderItem(r)->setText(RowHeader(kRows[r], QString::fromStdString(unit)));
    for (int c = 0; c < 5; ++c) table_->setItem(r, c, new QTableWidgetItem("—"));
  }
  for (SubsetMetric metric : kSubsetMetrics) ShowChart(charts_[ChartIndex(metric)], EmptyChart(metric, unit));
}

void StudyView::ShowStudy(const workflow::SessionStudy& study) {
  const workflow::StudyRecord& r = study.record;
  QString rank = QString::fromStdString(workflow::StudyRankSentence(r));
  rank[0] = rank[0].toUpper();
  const QString stale = study.Stale() ? "<span style=\"color:#c00\"><b>Stale:</b> " +
                                            QString::fromStdString(workflow::ListNames(study.changed_inputs)) +
                                            " changed after this study was made: run it again.</span><br>"
                                      : QString();
  rank_->setText(stale.isEmpty() ? "<b>" + rank.toHtmlEscaped() + "</b>"
                                 : stale + "<b>" + rank.toHtmlEscaped() + "</b>");
  about_->setText(
      Breakable(QString("IOOPS on %1%2 chose %3 of the %4 measured poses; %5 random %3-subsets (seed %6), each "
                        "calibrated from the nominal robot and validated by FK on the %7 poses it leaves out. "
                        "Made %8.")
                    .arg(CriterionName(r.criterion), r.weighted_selection ? " (weighted rows)" : " (unweighted)")
                    .arg(r.select)
                    .arg(r.measured)
                    .arg(r.random_count)
                    .arg(r.seed)
                    .arg(r.measured - r.select)
                    .arg(QString::fromStdString(r.created))));
  const QString unit = QString::fromStdString(r.length_unit);
  for (int row = 0; row < 6; ++row) {
    const workflow::StudyMetric& m = r.Metric(kRows[row]);
    table_->verticalHeaderItem(row)->setText(RowHeader(m.metric, unit));
    const QString cells[] = {MetricText(m.selected), MetricText(m.random.mean), MetricText(m.random.median),
                             MetricText(m.random.p5) + " – " + MetricText(m.random.p95),
                             std::isfinite(m.selected) ? FormatPercent(m.percentile) : "—"};
    for (int c = 0; c < 5; ++c) table_->setItem(row, c, new QTableWidgetItem(cells[c]));
  }
  for (SubsetMetric metric : kSubsetMetrics)
    ShowChart(charts_[ChartIndex(metric)],
              charts::StudyMetricChart(metric, study.RandomValuesOf(metric), r.Metric(metric).selected, r.select,
                                       r.length_unit));
}

}  // namespace hexcal::ui

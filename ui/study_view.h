// The section 8 study in the Validate step (docs/gui.md, "Section 8 study"):
// a form of the study's options (the table of workflow/study_options.h, as
// `hexcal study` has them; ui/option_form.h), *Run study* and *Cancel* with
// a progress bar, and the study the session keeps (SessionState::Study,
// session/session_study.h): where the selected subset ranks, a red line when
// the session changed since, the Table 5 figures and Figs. 19 and 18 (the
// charts of charts/figures.h, StudyMetricChart).
//
// The worker runs workflow::RunStudy without saving; the GUI thread then
// publishes study/ (SaveSessionStudy draws the figures with Qt, which only
// the GUI thread may) and reloads the session, so what is shown is always
// what the folder holds, as after `hexcal study` in a terminal.
//
//   auto* study = new StudyView(session);
//   study->SetOption("subsets", "500");
//   study->Run();  // then Job()->Running() until it is shown
#pragma once

#include <QString>
#include <QWidget>
#include <array>
#include <memory>
#include <string>

#include "ui/option_form.h"
#include "ui/qt_fwd.h"
#include "ui/session_state.h"
#include "workflow/study_step.h"

namespace hexcal::ui {

class StudyView : public QWidget {
  Q_OBJECT
 public:
  explicit StudyView(SessionState* session, QWidget* parent = nullptr);

  BackgroundJob* Job() const { return job_; }
  // Sets one option of the form by key ("select", "subsets", "criterion", ...).
  void SetOption(const std::string& key, const std::string& text);
  QLabel* RankLine() const { return rank_; }
  QTableWidget* Table() const { return table_; }
  // "done in 4.2 s on 2 threads; kept in study/.", "cancelled: study/ is unchanged.", ...
  const QString& LastOutcome() const { return outcome_; }

 public slots:
  void Run();
  void Refresh();

 private:
  void ResetForSession();
  void Finish(const std::shared_ptr<StatusOr<workflow::StudyOutcome>>& outcome);
  void ShowStudy(const workflow::SessionStudy& study);
  void ShowEmpty(const QString& why);
  void SetOutcome(const QString& text);

  SessionState* session_;
  BackgroundJob* job_;
  OptionRows options_;  // workflow::StudyOptions()
  QPushButton *run_, *cancel_;
  QProgressBar* progress_;
  QLabel *outcome_label_, *rank_, *about_;
  QTableWidget* table_;
  std::array<QtCharts::QChartView*, 6> charts_{};  // kSubsetMetrics order
  QString outcome_;
};

}  // namespace hexcal::ui

// The verdict on a calibration (report/calibration_verdict.h) in a panel:
// the level in its colour, then the findings that are not good with their
// advice, and the good ones on one line; every figure, threshold and meaning
// in the tooltip. Compact enough to sit above a table in a 1024×600 window:
// findings beyond four lines scroll. Fed by
// the Calibrate and Validate panels from the same Verdict the CLI prints.
//
//   auto* verdict = new VerdictView;
//   verdict->Show(workflow::MakeVerdict(report));
//   verdict->Show(workflow::MakeVerdict(report), "legs.csv changed since the results …");  // stale results
#pragma once

#include <QWidget>

#include "report/calibration_verdict.h"

class QLabel;
class QScrollArea;

namespace hexcal::ui {

class VerdictView : public QWidget {
  Q_OBJECT
 public:
  explicit VerdictView(QWidget* parent = nullptr);
  // `stale`: why the results judged are stale (SessionState::ResultsNote), shown
  // with the verdict, first, so that no verdict is seen without it (issue 40).
  void Show(const workflow::Verdict& verdict, const QString& stale = {});
  void Clear();               // no results: nothing shown
  QString LevelText() const;  // "good", "acceptable", "poor" or empty
  // Why the results are stale, or empty.
  QString StaleText() const { return stale_; }

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void FitFindings();

  QLabel *level_, *findings_;
  QScrollArea* findings_scroll_;
  QString level_text_;
  QString stale_;
};

}  // namespace hexcal::ui

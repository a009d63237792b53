// The verdict on a calibration (workflow/calibration_verdict.h) in a panel:
// the level in its colour, then the findings that are not good with their
// advice, and the good ones on one line; every figure, threshold and meaning
// in the tooltip. Compact enough to sit above a table in a 1024×600 window:
// findings beyond four lines scroll. Fed by
// the Calibrate and Validate panels from the same Verdict the CLI prints.
//
//   auto* verdict = new VerdictView;
//   verdict->Show(workflow::MakeVerdict(report));
#pragma once

#include <QWidget>

#include "workflow/calibration_verdict.h"

class QLabel;
class QScrollArea;

namespace hexcal::ui {

class VerdictView : public QWidget {
  Q_OBJECT
 public:
  explicit VerdictView(QWidget* parent = nullptr);
  void Show(const workflow::Verdict& verdict);
  void Clear();               // no results: nothing shown
  QString LevelText() const;  // "good", "acceptable", "poor" or empty

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void FitFindings();

  QLabel *level_, *findings_;
  QScrollArea* findings_scroll_;
  QString level_text_;
};

}  // namespace hexcal::ui

// The text a job printed (the summary `hexcal calibrate --session` prints),
// folded away under a "Run log" toggle: the panel shows its figures once, in
// its own form, and the raw lines stay one click away without taking the
// room of the table below (issue 35: the log, the same summary again and the
// verdict made the window taller than a 1280×720 screen).
//
//   auto* log = new RunLog;
//   log->SetText(QString::fromStdString(workflow::FormatCalibrationSummary(report)));
//   log->SetExpanded(true);  // what the toggle does
#pragma once

#include <QWidget>

class QPlainTextEdit;
class QToolButton;

namespace hexcal::ui {

class RunLog : public QWidget {
  Q_OBJECT
 public:
  explicit RunLog(QWidget* parent = nullptr);
  // Empty text: the toggle is disabled and the log folded.
  void SetText(const QString& text);
  QString Text() const;
  void SetExpanded(bool expanded);
  bool Expanded() const;

 private:
  QToolButton* toggle_;
  QPlainTextEdit* text_;
};

}  // namespace hexcal::ui

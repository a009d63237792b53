// Errors the operator can act on. Interactive: a message box. In --screenshot
// and test runs (SetInteractive(false)): one line on stderr, never blocking.
#pragma once

#include <QString>

class QWidget;

namespace hexcal::ui {

void SetInteractive(bool interactive);
bool Interactive();
// `what` is the step that failed ("Plan", "Open session"); `message` says what to fix.
void ShowError(QWidget* parent, const QString& what, const QString& message);
void ShowInfo(QWidget* parent, const QString& what, const QString& message);

}  // namespace hexcal::ui

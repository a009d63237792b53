// The workflow's messages in the GUI's terms (issue 35). The workflow's
// sentences are shared with the CLI, which names its commands and flags
// ("it needs --controller sim", "run hexcal calibrate --session again"); the
// GUI names its own controls instead ("choose 'sim' in the Controller list",
// "run the Calibrate step again"). Every error dialog, the step list's
// sentences, the panels' outcome lines and the verdict's advice go through
// it; the run log keeps the CLI's lines as they are (it says so).
//
//   ShowError(this, "Connect", InGuiTerms(QString::fromStdString(status.message())));
#pragma once

#include <QString>

namespace hexcal::ui {

QString InGuiTerms(const QString& text);

}  // namespace hexcal::ui

// Errors the operator can act on. Interactive: a message box. In --screenshot
// and test runs (SetInteractive(false)): one line on stderr, never blocking.
// Message boxes show their text as plain text: it quotes file names.
//
//   SetInteractive(false);  // tests and --screenshot: one line on stderr
//   ShowError(window, "Open session", QString::fromStdString(status.message()));
#pragma once

#include <QString>
#include <QStringList>
#include <functional>

#include "workflow/session_edits.h"

class QWidget;

namespace hexcal::ui {

void SetInteractive(bool interactive);
bool Interactive();
// `what` is the step that failed ("Plan", "Open session"); `message` says what to fix.
void ShowError(QWidget* parent, const QString& what, const QString& message);
void ShowInfo(QWidget* parent, const QString& what, const QString& message);
// The last ShowError's "what: message" as shown (tests read what the operator was told).
QString LastShownError();

// Runs an edit of the session's files (workflow/session_edits.h). When the
// file changed on disk under the operator's edit, asks whether to apply it
// anyway ("Use mine") or keep the file as it is ("Keep theirs", also the
// answer when not interactive); errors are shown. True when the edit was made.
bool ApplySessionEdit(QWidget* parent, const QString& what,
                      const std::function<workflow::EditOutcome(bool overwrite)>& edit);

// Who answers the conflict question: the operator in a message box, unless
// tests set an answer (true: "Use mine"). `text` says what changed on disk.
using ConflictAnswerer = std::function<bool(const QString& what, const QString& text)>;
// An empty function restores the message box (keep theirs when not interactive).
void SetConflictAnswerer(ConflictAnswerer answerer);

// A question with several answers (`choices`, button texts, the last one the
// answer of Escape or closing the box); returns the index of the one picked.
// `fallback` is the default button, and the answer when not interactive
// (--screenshot, tests without an answerer).
int AskChoice(QWidget* parent, const QString& what, const QString& text, const QString& detail,
              const QStringList& choices, int fallback);
using ChoiceAnswerer = std::function<int(const QString& what, const QString& text, const QStringList& choices)>;
// An empty function restores the message box.
void SetChoiceAnswerer(ChoiceAnswerer answerer);

// Before exporting or reporting stale results: `reason` says what changed
// since they were computed. True when the operator goes on anyway ("Use the
// stale results"); false on Cancel, and when not interactive, unless tests
// set an answer (SetStaleAnswerer; an empty function restores the box).
bool ConfirmStale(QWidget* parent, const QString& what, const QString& reason);
void SetStaleAnswerer(ConflictAnswerer answerer);

}  // namespace hexcal::ui

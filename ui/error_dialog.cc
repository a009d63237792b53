#include "ui/error_dialog.h"

#include <QMessageBox>
#include <QPushButton>
#include <iostream>
#include <vector>

#include "ui/gui_terms.h"

namespace hexcal::ui {
namespace {
bool interactive = true;
ConflictAnswerer answerer;        // empty: ask in a message box
ConflictAnswerer stale_answerer;  // the same for ConfirmStale
ChoiceAnswerer choice_answerer;
QString last_error;

void Show(QWidget* parent, QMessageBox::Icon icon, const QString& what, const QString& message) {
  QMessageBox box(icon, "hexcal — " + what, message, QMessageBox::Ok, parent);
  box.setTextFormat(Qt::PlainText);
  box.exec();
}

// "Use mine" (true) or "Keep theirs" (false).
bool AskUseMine(QWidget* parent, const QString& what, const QString& text) {
  if (answerer) return answerer(what, text);
  if (!interactive) return false;  // keep theirs: never write over what another program wrote
  QMessageBox box(QMessageBox::Question, "hexcal — " + what, text, QMessageBox::NoButton, parent);
  box.setTextFormat(Qt::PlainText);
  box.setInformativeText("Apply your change over it, or keep the file as it is on disk (your change is dropped)?");
  QPushButton* mine = box.addButton("Use mine", QMessageBox::AcceptRole);
  box.addButton("Keep theirs", QMessageBox::RejectRole);
  box.exec();
  return box.clickedButton() == mine;
}

}  // namespace

void SetInteractive(bool value) { interactive = value; }
QString LastShownError() { return last_error; }
void SetChoiceAnswerer(ChoiceAnswerer value) { choice_answerer = std::move(value); }

int AskChoice(QWidget* parent, const QString& what, const QString& text, const QString& detail,
              const QStringList& choices, int fallback) {
  if (choice_answerer) return choice_answerer(what, text, choices);
  std::cerr << "hexcal-gui: " << what.toStdString() << ": " << text.toStdString() << "\n";
  if (!interactive) return fallback;
  QMessageBox box(QMessageBox::Question, "hexcal — " + what, text, QMessageBox::NoButton, parent);
  box.setTextFormat(Qt::PlainText);
  box.setInformativeText(detail);
  std::vector<QPushButton*> buttons;
  for (const QString& choice : choices) buttons.push_back(box.addButton(choice, QMessageBox::ActionRole));
  box.setDefaultButton(buttons[fallback]);
  box.setEscapeButton(buttons.back());
  box.exec();
  for (size_t k = 0; k < buttons.size(); ++k)
    if (box.clickedButton() == buttons[k]) return static_cast<int>(k);
  return static_cast<int>(buttons.size()) - 1;
}
void SetConflictAnswerer(ConflictAnswerer value) { answerer = std::move(value); }
void SetStaleAnswerer(ConflictAnswerer value) { stale_answerer = std::move(value); }

bool ConfirmStale(QWidget* parent, const QString& what, const QString& reason) {
  std::cerr << "hexcal-gui: " << what.toStdString() << ": " << reason.toStdString() << "\n";
  if (stale_answerer) return stale_answerer(what, reason);
  if (!interactive) return false;  // never act on stale results unasked
  QMessageBox box(QMessageBox::Warning, "hexcal — " + what, reason, QMessageBox::NoButton, parent);
  box.setTextFormat(Qt::PlainText);
  box.setInformativeText("Calibrate again first (Calibrate step), or go on with these results?");
  QPushButton* cancel = box.addButton(QMessageBox::Cancel);
  QPushButton* anyway = box.addButton("Use the stale results", QMessageBox::AcceptRole);
  box.setDefaultButton(cancel);
  box.exec();
  return box.clickedButton() == anyway;
}
bool Interactive() { return interactive; }

void ShowError(QWidget* parent, const QString& what, const QString& text) {
  const QString message = InGuiTerms(text);  // the workflow's messages name the CLI's flags
  last_error = what + ": " + message;
  std::cerr << "hexcal-gui: " << what.toStdString() << ": " << message.toStdString() << "\n";
  if (interactive) Show(parent, QMessageBox::Warning, what, message);
}

void ShowInfo(QWidget* parent, const QString& what, const QString& text) {
  const QString message = InGuiTerms(text);
  if (interactive) {
    Show(parent, QMessageBox::Information, what, message);
  } else {
    std::cerr << "hexcal-gui: " << what.toStdString() << ": " << message.toStdString() << "\n";
  }
}

bool ApplySessionEdit(QWidget* parent, const QString& what,
                      const std::function<workflow::EditOutcome(bool overwrite)>& edit) {
  workflow::EditOutcome done = edit(false);
  if (done.conflict) {
    std::cerr << "hexcal-gui: " << what.toStdString() << ": " << done.conflict_text << "\n";
    if (!AskUseMine(parent, what, QString::fromStdString(done.conflict_text))) return false;
    done = edit(true);
  }
  if (!done.status.ok()) {
    ShowError(parent, what, QString::fromStdString(done.status.message()));
    return false;
  }
  return !done.conflict;
}

}  // namespace hexcal::ui

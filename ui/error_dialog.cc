#include "ui/error_dialog.h"

#include <QMessageBox>
#include <iostream>

namespace hexcal::ui {
namespace {
bool interactive = true;
}

void SetInteractive(bool value) { interactive = value; }
bool Interactive() { return interactive; }

void ShowError(QWidget* parent, const QString& what, const QString& message) {
  std::cerr << "hexcal-gui: " << what.toStdString() << ": " << message.toStdString() << "\n";
  if (interactive) QMessageBox::warning(parent, "hexcal — " + what, message);
}

void ShowInfo(QWidget* parent, const QString& what, const QString& message) {
  if (interactive) {
    QMessageBox::information(parent, "hexcal — " + what, message);
  } else {
    std::cerr << "hexcal-gui: " << what.toStdString() << ": " << message.toStdString() << "\n";
  }
}

}  // namespace hexcal::ui

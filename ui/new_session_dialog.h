// File > New session: the folder, and the robot, camera and target it names
// (presets or files), and the noise model, as `hexcal session init` takes them.
//
//   NewSessionDialog dialog(this);
//   if (dialog.exec() == QDialog::Accepted) session->Create(dialog.Folder(), dialog.Config());
#pragma once

#include <QDialog>

#include "core/session.h"
#include "ui/option_form.h"

class QComboBox;
class QLineEdit;

namespace hexcal::ui {

class NewSessionDialog : public QDialog {
  Q_OBJECT
 public:
  explicit NewSessionDialog(QWidget* parent = nullptr);
  QString Folder() const;
  SessionConfig Config() const;

 private:
  QLineEdit* folder_;
  QComboBox* robot_;
  QLineEdit *camera_, *target_;
  OptionRows noise_;  // NoiseModelOptions()
};

}  // namespace hexcal::ui

// File > New session: the folder, the robot it names (a preset or a file),
// what measures the platform's pose, and the noise model, as `hexcal session
// init` takes them. The instrument is a camera (its camera and target) or a
// laser tracker or CMM (`--instrument points`: the points file, which may not
// exist yet, an optional reflector file, checked now, and the σ of a point
// coordinate, 0.02 mm in the robot's unit by default; docs/session.md).
//
//   NewSessionDialog dialog(this);
//   if (dialog.exec() == QDialog::Accepted) session->Create(dialog.Folder(), dialog.Config());
#pragma once

#include <QDialog>

#include "core/robot.h"
#include "core/session.h"
#include "ui/option_form.h"

class QComboBox;
class QFormLayout;
class QLabel;
class QLineEdit;

namespace hexcal::ui {

class NewSessionDialog : public QDialog {
  Q_OBJECT
 public:
  explicit NewSessionDialog(QWidget* parent = nullptr);
  QString Folder() const;
  // The files named as session.yaml keeps them: a file inside the folder
  // relative to it, one elsewhere as given (a relative name is the folder's).
  SessionConfig Config() const;
  // Why the values cannot make a session (a points session without its
  // points file, a reflector file that does not load, a σ not positive); ok
  // when they can. OK checks it before closing the dialog.
  Status Check() const;

 private:
  void ShowInstrumentRows();
  void RobotChanged(const QString& robot);  // the σ's unit, and its default while not typed
  QWidget* FileRow(QLineEdit* field, bool save);

  QFormLayout* form_;
  QLineEdit* folder_;
  QComboBox* robot_;
  QComboBox* instrument_;  // "camera", "points"
  QLineEdit *camera_, *target_;
  QLineEdit *points_, *reflectors_, *point_sigma_;
  QLabel* sigma_unit_;
  LengthUnit unit_ = LengthUnit::kMillimetre;
  bool sigma_typed_ = false;
  OptionRows noise_;  // NoiseModelOptions()
};

}  // namespace hexcal::ui

#include "ui/new_session_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>

#include "core/robot_io.h"

namespace hexcal::ui {

NewSessionDialog::NewSessionDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle("New session");
  folder_ = new QLineEdit;
  auto* browse = new QPushButton("Browse…");
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString dir = QFileDialog::getSaveFileName(this, "New session folder");
    if (!dir.isEmpty()) folder_->setText(dir);
  });
  robot_ = new QComboBox;
  robot_->setEditable(true);
  for (const std::string& name : PresetNames()) robot_->addItem(QString::fromStdString(name));
  robot_->setToolTip("A robot preset, or the path of a robot file (docs/robot-file.md)");
  camera_ = new QLineEdit("sim-4.2mm-1024x768");
  camera_->setToolTip("A camera preset or an OpenCV/ROS camera file; the Measure step can calibrate one");
  target_ = new QLineEdit("aprilgrid-6x6");
  target_->setToolTip("A target preset or a target YAML (Kalibr names)");
  auto* folder_row = new QHBoxLayout;
  folder_row->addWidget(folder_, 1);
  folder_row->addWidget(browse);
  auto* form = new QFormLayout(this);
  form->addRow("Folder", folder_row);
  form->addRow("Robot", robot_);
  form->addRow("Camera", camera_);
  form->addRow("Target", target_);
  // A camera's pose noise is larger than the paper's laser tracker's.
  NoiseModel noise;
  noise.position = 0.005;
  noise.angle_deg = 0.02;
  noise_ = AddOptionRows(form, NoiseModelOptions(), noise);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  form->addRow(buttons);
}

QString NewSessionDialog::Folder() const { return folder_->text(); }

SessionConfig NewSessionDialog::Config() const {
  SessionConfig config;
  config.robot = robot_->currentText().toStdString();
  config.camera = camera_->text().toStdString();
  config.target = target_->text().toStdString();
  StatusOr<NoiseModel> noise = ReadOptionRows(NoiseModelOptions(), noise_);
  if (noise.ok()) config.noise = *noise;  // the spin boxes hold values in range
  return config;
}

}  // namespace hexcal::ui

#include "ui/new_session_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>

#include "core/robot_io.h"

namespace hexcal::ui {
namespace {

QDoubleSpinBox* Noise(double value, const QString& suffix, const QString& tip) {
  auto* box = new QDoubleSpinBox;
  box->setDecimals(4);
  box->setRange(0, 10);
  box->setSingleStep(0.001);
  box->setValue(value);
  box->setSuffix(suffix);
  box->setToolTip(tip);
  return box;
}

}  // namespace

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
  noise_position_ = Noise(0.005, " (robot unit)", "Half-width of the camera's position noise");
  noise_angle_ = Noise(0.02, " °", "Half-width of the camera's angle noise");
  noise_leg_ = Noise(0.001, " (robot unit)", "Half-width of the leg sensors' noise");
  auto* folder_row = new QHBoxLayout;
  folder_row->addWidget(folder_, 1);
  folder_row->addWidget(browse);
  auto* form = new QFormLayout(this);
  form->addRow("Folder", folder_row);
  form->addRow("Robot", robot_);
  form->addRow("Camera", camera_);
  form->addRow("Target", target_);
  form->addRow("Noise: position", noise_position_);
  form->addRow("Noise: angle", noise_angle_);
  form->addRow("Noise: leg reading", noise_leg_);
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
  config.noise.position = noise_position_->value();
  config.noise.angle_deg = noise_angle_->value();
  config.noise.leg = noise_leg_->value();
  return config;
}

}  // namespace hexcal::ui

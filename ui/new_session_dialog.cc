#include "ui/new_session_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>

#include "core/csv.h"
#include "core/point_file.h"
#include "core/robot_io.h"
#include "ui/error_dialog.h"

namespace hexcal::ui {
namespace {

constexpr double kDefaultPointSigmaMm = 0.02;  // a laser tracker's, as `session init --point-sigma`

QString Sigma(double value) { return QString::number(value, 'g', 6); }

}  // namespace

NewSessionDialog::NewSessionDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle("New session");
  folder_ = new QLineEdit;
  folder_->setObjectName("folder");
  auto* browse = new QPushButton("Browse…");
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString dir = QFileDialog::getSaveFileName(this, "New session folder");
    if (!dir.isEmpty()) folder_->setText(dir);
  });
  robot_ = new QComboBox;
  robot_->setEditable(true);
  robot_->setObjectName("robot");
  for (const std::string& name : PresetNames()) robot_->addItem(QString::fromStdString(name));
  robot_->setToolTip("A robot preset, or the path of a robot file (docs/robot-file.md)");
  instrument_ = new QComboBox;
  instrument_->setObjectName("instrument");
  instrument_->addItem("camera: images of an AprilTag board", "camera");
  instrument_->addItem("points: a laser tracker's or CMM's named 3D points", "points");
  instrument_->setToolTip("What measures the platform's pose at each row of legs.csv (docs/session.md)");
  camera_ = new QLineEdit("sim-4.2mm-1024x768");
  camera_->setToolTip("A camera preset or an OpenCV/ROS camera file; the Measure step can calibrate one");
  target_ = new QLineEdit("aprilgrid-6x6");
  target_->setToolTip("A target preset or a target YAML (Kalibr names)");
  points_ = new QLineEdit("points.txt");
  points_->setObjectName("points");
  points_->setToolTip("The tracker's export, robot unit: CSV pose,point,x,y,z[,sigma] or SpatialAnalyzer's ASCII "
                      "(collection group target x y z [sigma]). It may be written later; a name without a folder is "
                      "in the session folder.");
  reflectors_ = new QLineEdit;
  reflectors_->setObjectName("reflectors");
  reflectors_->setPlaceholderText("none: estimated from the poses");
  reflectors_->setToolTip("Optional: the reflectors' positions in a frame fixed to the platform, CSV point,x,y,z. "
                          "Without it their shape is estimated from the measured poses.");
  point_sigma_ = new QLineEdit;
  point_sigma_->setObjectName("point_sigma");
  point_sigma_->setToolTip("σ of each coordinate of a point the points file gives none for, robot unit "
                           "(a laser tracker: about 0.02 mm)");
  connect(point_sigma_, &QLineEdit::textEdited, this, [this] { sigma_typed_ = true; });
  sigma_unit_ = new QLabel;
  auto* sigma_row = new QWidget;
  auto* sigma_layout = new QHBoxLayout(sigma_row);
  sigma_layout->setContentsMargins(0, 0, 0, 0);
  sigma_layout->addWidget(point_sigma_, 1);
  sigma_layout->addWidget(sigma_unit_);
  auto* folder_row = new QHBoxLayout;
  folder_row->addWidget(folder_, 1);
  folder_row->addWidget(browse);
  form_ = new QFormLayout(this);
  form_->addRow("Folder", folder_row);
  form_->addRow("Robot", robot_);
  form_->addRow("Measured by", instrument_);
  form_->addRow("Camera", camera_);
  form_->addRow("Target", target_);
  form_->addRow("Points file", FileRow(points_, /*save=*/true));
  form_->addRow("Reflectors", FileRow(reflectors_, /*save=*/false));
  form_->addRow("Point σ", sigma_row);
  // A camera's pose noise is larger than the paper's laser tracker's.
  NoiseModel noise;
  noise.position = 0.005;
  noise.angle_deg = 0.02;
  noise_ = AddOptionRows(form_, NoiseModelOptions(), noise);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    const Status checked = Check();
    if (!checked.ok()) return ShowError(this, "New session", QString::fromStdString(checked.message()));
    accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  form_->addRow(buttons);
  connect(instrument_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { ShowInstrumentRows(); });
  connect(robot_, &QComboBox::currentTextChanged, this, &NewSessionDialog::RobotChanged);
  RobotChanged(robot_->currentText());
  ShowInstrumentRows();
}

// The field and a Browse button; the points file may not exist yet.
QWidget* NewSessionDialog::FileRow(QLineEdit* field, bool save) {
  auto* row = new QWidget;
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* browse = new QPushButton("Browse…");
  connect(browse, &QPushButton::clicked, this, [this, field, save] {
    const QString file = save ? QFileDialog::getSaveFileName(this, "Points file (may not exist yet)", {}, {}, nullptr,
                                                             QFileDialog::DontConfirmOverwrite)
                              : QFileDialog::getOpenFileName(this, "Reflector file", {}, "CSV (*.csv);;All (*)");
    if (!file.isEmpty()) field->setText(file);
  });
  layout->addWidget(field, 1);
  layout->addWidget(browse);
  return row;
}

void NewSessionDialog::ShowInstrumentRows() {
  const bool points = instrument_->currentData().toString() == "points";
  for (QWidget* field : {static_cast<QWidget*>(camera_), static_cast<QWidget*>(target_)}) {
    field->setVisible(!points);
    form_->labelForField(field)->setVisible(!points);
  }
  for (QLineEdit* field : {points_, reflectors_, point_sigma_}) {
    QWidget* row = field->parentWidget() != this ? field->parentWidget() : field;
    row->setVisible(points);
    if (QWidget* label = form_->labelForField(row)) label->setVisible(points);
  }
  adjustSize();
}

void NewSessionDialog::RobotChanged(const QString& robot) {
  StatusOr<Robot> loaded = LoadRobot(robot.toStdString());
  if (loaded.ok()) unit_ = loaded->length_unit;  // else the last unit that loaded
  sigma_unit_->setText(LengthUnitName(unit_));
  if (!sigma_typed_) point_sigma_->setText(Sigma(kDefaultPointSigmaMm * 0.001 / MetresPerUnit(unit_)));
}

QString NewSessionDialog::Folder() const { return folder_->text(); }

SessionConfig NewSessionDialog::Config() const {
  SessionConfig config;
  config.robot = robot_->currentText().toStdString();
  StatusOr<NoiseModel> noise = ReadOptionRows(NoiseModelOptions(), noise_);
  if (noise.ok()) config.noise = *noise;  // the spin boxes hold values in range
  if (instrument_->currentData().toString() != "points") {
    config.camera = camera_->text().toStdString();
    config.target = target_->text().toStdString();
    return config;
  }
  config.instrument = Instrument::kPoints;
  const QDir folder(QDir(Folder()).absolutePath());
  const auto as_kept = [&](const QLineEdit* field) {
    const QString name = field->text().trimmed();
    if (name.isEmpty() || QDir::isRelativePath(name)) return name.toStdString();
    const QString relative = folder.relativeFilePath(QDir::cleanPath(name));
    return (relative.startsWith("..") ? QDir::cleanPath(name) : relative).toStdString();
  };
  config.points = as_kept(points_);
  config.reflectors = as_kept(reflectors_);
  config.point_sigma = point_sigma_->text().toDouble();
  return config;
}

Status NewSessionDialog::Check() const {
  if (Folder().trimmed().isEmpty()) return Status::BadInput("Choose the session's folder.");
  const SessionConfig config = Config();
  if (config.instrument != Instrument::kPoints) return Status::Ok();
  bool number = false;
  const double sigma = point_sigma_->text().toDouble(&number);
  if (!number || !(sigma > 0 && sigma < 1e6))
    return Status::BadInput("Point σ: a positive length in the robot's unit (" + std::string(LengthUnitName(unit_)) +
                            ")");
  if (config.points.empty())
    return Status::BadInput("A points session needs its points file (it may be written later).");
  if (config.reflectors.empty()) return Status::Ok();
  // The reflector file is checked now, as `hexcal session init` does.
  const QString path = QDir(QDir(Folder()).absolutePath()).filePath(QString::fromStdString(config.reflectors));
  StatusOr<std::vector<NamedPoint>> parsed = LoadReflectorFile(path.toStdString(), config.reflectors);
  return parsed.ok() ? Status::Ok() : parsed.status();
}

}  // namespace hexcal::ui

#include "ui/plan_visibility.h"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>
#include <cmath>

#include "core/pose.h"
#include "ui/quantity_format.h"
#include "ui/text_wrap.h"

namespace hexcal::ui {
namespace {

enum Source { kOff = 0, kSession = 1, kFile = 2 };

// Registered frames and the camera's intrinsics: the field of view is the
// image's, from the focal lengths (a pinhole's; distortion widens it a little).
StatusOr<MeasurementConstraints> FromSession(const SessionState& session) {
  const SessionConfig& config = session.Config();
  if (!config.base_from_camera || !config.platform_from_target)
    return Status::BadInput(
        "the session has no registered camera and target yet (they are found by the first "
        "calibration); choose a settings file instead");
  if (!session.SessionCamera()) return Status::BadInput("the session's camera does not load");
  const Camera& camera = *session.SessionCamera();
  MeasurementConstraints constraints;
  constraints.base_from_camera = *config.base_from_camera;
  constraints.platform_from_target = *config.platform_from_target;
  constraints.half_fov_x_deg = RadToDeg(std::atan(0.5 * camera.width / camera.fx));
  constraints.half_fov_y_deg = RadToDeg(std::atan(0.5 * camera.height / camera.fy));
  return constraints;
}

}  // namespace

QString DescribeConstraints(const MeasurementConstraints& c, const QString& unit) {
  const Eigen::Vector3d& p = c.base_from_camera.position;
  return QString("camera at (%1, %2, %3) %4, field of view %5 × %6, view angle ≤ %7")
      .arg(FormatCoordinate(p.x()), FormatCoordinate(p.y()), FormatCoordinate(p.z()), unit,
           FormatAngle(2 * c.half_fov_x_deg), FormatAngle(2 * c.half_fov_y_deg), FormatAngle(c.max_view_angle_deg));
}

VisibilityForm::VisibilityForm(SessionState* session, QWidget* parent) : QWidget(parent), session_(session) {
  source_ = new QComboBox;
  source_->setObjectName("visibility_source");
  source_->addItems({"off", "the session's registered camera", "a plan settings file"});
  source_->setToolTip("Keep the target measurable at every planned pose (docs/planner.md, settings file)");
  file_ = new QLineEdit;
  file_->setPlaceholderText("plan.yaml (camera, target, field_of_view_deg, max_view_angle_deg)");
  auto* browse = new QPushButton("…");
  browse->setMaximumWidth(32);
  summary_ = new QLabel;
  summary_->setWordWrap(true);
  summary_->setTextFormat(Qt::PlainText);
  summary_->setObjectName("visibility_summary");
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, "Plan settings", {}, "YAML (*.yaml *.yml)");
    if (!file.isEmpty()) Choose(file);
  });
  for (auto changed : {&VisibilityForm::Describe, &VisibilityForm::Chosen}) {
    connect(source_, qOverload<int>(&QComboBox::currentIndexChanged), this, changed);
    connect(file_, &QLineEdit::editingFinished, this, changed);
  }
  connect(session_, &SessionState::Changed, this, &VisibilityForm::Describe);
  file_row_ = new QWidget;  // shown for a settings file only: the Plan column is short at 1024×600
  auto* file_row = new QHBoxLayout(file_row_);
  file_row->setContentsMargins(0, 0, 0, 0);
  file_row->addWidget(file_, 1);
  file_row->addWidget(browse);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(new QLabel("Camera visibility:"));
  layout->addWidget(source_);
  layout->addWidget(file_row_);
  layout->addWidget(summary_);
  Describe();
}

StatusOr<std::optional<MeasurementConstraints>> VisibilityForm::Constraints() const {
  switch (source_->currentIndex()) {
    case kSession: {
      StatusOr<MeasurementConstraints> constraints = FromSession(*session_);
      if (!constraints.ok()) return Status::BadInput("Camera visibility: " + constraints.status().message());
      return std::optional<MeasurementConstraints>(*constraints);
    }
    case kFile: {
      StatusOr<PlanSettings> settings = LoadPlanSettings(file_->text().toStdString(), session_->NominalRobot());
      if (!settings.ok()) return Status::BadInput("Camera visibility: " + settings.status().message());
      if (!settings->measurement)
        return Status::BadInput("Camera visibility: " + file_->text().toStdString() + " has no camera: section");
      return settings->measurement;
    }
    default:
      return std::optional<MeasurementConstraints>();
  }
}

void VisibilityForm::Choose(const QString& source) {
  if (source == "off") {
    source_->setCurrentIndex(kOff);
  } else if (source == "session") {
    source_->setCurrentIndex(kSession);
  } else {
    file_->setText(source);
    source_->setCurrentIndex(kFile);
  }
  Describe();
  emit Chosen();
}

void VisibilityForm::Reset() {
  file_->clear();
  source_->setCurrentIndex(kOff);
  Describe();
  emit Chosen();
}

void VisibilityForm::Describe() {
  file_row_->setVisible(source_->currentIndex() == kFile);
  if (!session_->IsOpen() || source_->currentIndex() == kOff)
    return summary_->setText("Poses are planned without regard to the camera.");
  StatusOr<std::optional<MeasurementConstraints>> constraints = Constraints();
  if (!constraints.ok()) return summary_->setText(Breakable(QString::fromStdString(constraints.status().message())));
  summary_->setText(DescribeConstraints(**constraints, LengthUnitName(session_->NominalRobot().length_unit)));
}

}  // namespace hexcal::ui

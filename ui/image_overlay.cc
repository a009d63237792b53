#include "ui/image_overlay.h"

#include <QPainter>
#include <memory>

#include "vision/measure.h"

namespace hexcal::ui {

OverlayResult DetectAndDraw(const QString& file, const Camera& camera, const Target& target) {
  OverlayResult result;
  StatusOr<cv::Mat> gray = LoadGrayImage(file.toStdString());
  if (!gray.ok()) {
    result.status = "unreadable: " + QString::fromStdString(gray.status().message());
    return result;
  }
  StatusOr<std::unique_ptr<TagDetector>> detector =
      TagDetector::Create(ForTarget(DetectorOptions{}, target), std::make_shared<const IdealPixelMap>(camera));
  if (!detector.ok()) {
    result.status = QString::fromStdString(detector.status().message());
    return result;
  }
  const Detections detections = (*detector)->Detect(*gray);
  const BoardObservation observation = MatchToTarget(target, detections);
  const BoardPose pose = EstimateBoardPose(camera, observation, BoardPoseOptions{});
  result.ok = pose.status == PoseStatus::kOk;
  result.rms_px = pose.rms_px;
  result.tags = observation.NumTags();
  result.status = PoseStatusName(pose.status);
  if (!pose.message.empty()) result.status += ": " + QString::fromStdString(pose.message);

  const QImage source(gray->data, gray->cols, gray->rows, static_cast<int>(gray->step), QImage::Format_Grayscale8);
  result.image = source.convertToFormat(QImage::Format_RGB32);  // deep copy: `gray` dies here
  QPainter painter(&result.image);
  painter.setRenderHint(QPainter::Antialiasing);
  const double line = std::max(1.5, result.image.width() / 600.0);
  QFont font = painter.font();
  font.setPixelSize(std::max(10, result.image.width() / 60));
  painter.setFont(font);
  // OpenCV pixel centres are at integer coordinates; Qt's at +0.5.
  const auto to_qt = [](const Eigen::Vector2d& p) { return QPointF(p.x() + 0.5, p.y() + 0.5); };
  for (const TagDetection& tag : detections.tags) {
    QPolygonF outline;
    for (const Eigen::Vector2d& corner : tag.corners) outline << to_qt(corner);
    painter.setPen(QPen(QColor(0, 200, 0), line));
    painter.drawPolygon(outline);
    painter.setPen(QColor(0, 120, 255));
    painter.drawText(outline.boundingRect(), Qt::AlignCenter, QString::number(tag.id));
  }
  if (pose.has_pose) {
    // The whole board reprojected, seen tags or not: a wrong pose shows at once.
    painter.setPen(QPen(QColor(230, 0, 0), 0.6 * line));
    for (int index = 0; index < target.NumTags(); ++index) {
      QPolygonF outline;
      for (const Eigen::Vector3d& corner : target.TagCorners(target.TagId(index)))
        outline << to_qt(camera.Project(pose.camera_from_target * corner));
      painter.drawPolygon(outline);
    }
  }
  return result;
}

}  // namespace hexcal::ui

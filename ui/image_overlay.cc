#include "ui/image_overlay.h"

#include <QPainter>
#include <memory>

#include "vision/measure.h"

#include <opencv2/imgproc.hpp>

namespace hexcal::ui {

namespace {

double Sharpness(const cv::Mat& gray) {
  cv::Mat laplacian;
  cv::Laplacian(gray, laplacian, CV_64F);
  cv::Scalar mean, deviation;
  cv::meanStdDev(laplacian, mean, deviation);
  return deviation[0] * deviation[0];
}

bool InsideImage(const Eigen::Vector2d& p, const cv::Mat& image) {
  return p.x() >= 0 && p.y() >= 0 && p.x() <= image.cols - 1 && p.y() <= image.rows - 1;
}

}  // namespace

OverlayResult DetectAndDraw(const QString& file, const Camera& camera, const Target& target) {
  StatusOr<cv::Mat> gray = LoadGrayImage(file.toStdString());
  if (!gray.ok()) {
    OverlayResult result;
    result.status = "unreadable: " + QString::fromStdString(gray.status().message());
    return result;
  }
  return DetectAndDraw(*gray, camera, target);
}

QString ReadinessProblem(const OverlayResult& overlay) {
  if (!overlay.ok) return "no board pose: " + overlay.status;
  if (!overlay.whole_board_in_view) return "part of the board is outside the image";
  if (overlay.rms_px > kReadyMaxRmsPx) return QString("reprojection RMS above %1 px").arg(kReadyMaxRmsPx);
  if (overlay.sharpness < kReadyMinSharpness) return "the image is blurred";
  return {};
}

OverlayResult DetectAndDraw(const cv::Mat& frame, const Camera& camera, const Target& target) {
  OverlayResult result;
  cv::Mat grey_frame;
  if (frame.channels() == 3) {
    cv::cvtColor(frame, grey_frame, cv::COLOR_BGR2GRAY);
  } else {
    grey_frame = frame;
  }
  const cv::Mat* gray = &grey_frame;
  if (gray->empty() || gray->type() != CV_8UC1) {
    result.status = "unreadable: not an 8-bit grey or colour frame";
    return result;
  }
  result.sharpness = Sharpness(*gray);
  result.board_tags = target.NumTags();
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
    result.whole_board_in_view = true;
    for (int index = 0; index < target.NumTags(); ++index) {
      QPolygonF outline;
      for (const Eigen::Vector3d& corner : target.TagCorners(target.TagId(index))) {
        const Eigen::Vector2d pixel = camera.Project(pose.camera_from_target * corner);
        result.whole_board_in_view = result.whole_board_in_view && InsideImage(pixel, *gray);
        outline << to_qt(pixel);
      }
      painter.drawPolygon(outline);
    }
  }
  return result;
}

}  // namespace hexcal::ui

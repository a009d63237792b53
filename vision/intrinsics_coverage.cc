// The corner coverage of an intrinsic calibration (intrinsics.h): its
// figure and its picture.
#include <algorithm>
#include <iterator>
#include <opencv2/imgproc.hpp>

#include "core/csv.h"
#include "vision/intrinsics.h"

namespace hexcal {

double CoverageFraction(const IntrinsicsResult& result) {
  constexpr int kCols = 8, kRows = 6;
  bool seen[kRows][kCols] = {};
  for (const CalibrationView& view : result.views) {
    if (!view.used) continue;
    for (const Eigen::Vector2d& p : view.corners) {
      const int c = std::clamp(static_cast<int>(p.x() * kCols / result.camera.width), 0, kCols - 1);
      const int r = std::clamp(static_cast<int>(p.y() * kRows / result.camera.height), 0, kRows - 1);
      seen[r][c] = true;
    }
  }
  int count = 0;
  for (const auto& row : seen) count += static_cast<int>(std::count(std::begin(row), std::end(row), true));
  return static_cast<double>(count) / (kCols * kRows);
}

cv::Mat CoverageImage(const IntrinsicsResult& result) {
  const int width = result.camera.width, height = result.camera.height;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(32, 32, 32));
  for (int c = 1; c < 8; ++c) {
    cv::line(image, {c * width / 8, 0}, {c * width / 8, height - 1}, cv::Scalar(70, 70, 70), 1);
  }
  for (int r = 1; r < 6; ++r) {
    cv::line(image, {0, r * height / 6}, {width - 1, r * height / 6}, cv::Scalar(70, 70, 70), 1);
  }
  const int radius = std::max(2, width / 400);
  int used_index = 0;
  for (const CalibrationView& view : result.views) {
    cv::Scalar colour(110, 110, 110);
    if (view.used) {
      cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((used_index++ * 37) % 180, 220, 255)), bgr;
      cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
      const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
      colour = cv::Scalar(c[0], c[1], c[2]);
    }
    for (const Eigen::Vector2d& p : view.corners) {
      cv::circle(image, cv::Point(cvRound(p.x() * 16), cvRound(p.y() * 16)), radius * 16, colour, cv::FILLED,
                 cv::LINE_AA, 4);
    }
  }
  const std::string text = "corner coverage " + FormatSignificant(100 * CoverageFraction(result)) + " % of 8 x 6 cells, " +
                           std::to_string(result.used_views) + " views, RMS " + FormatSignificant(result.rms_px) + " px";
  const double scale = std::max(0.4, width / 1600.0);
  cv::putText(image, text, {10, height - 12}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return image;
}

}  // namespace hexcal

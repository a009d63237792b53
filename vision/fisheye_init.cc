#include "vision/fisheye_init.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

namespace hexcal {
namespace {

// Rays further than this from the axis are left out of the pose: the
// plane's projective coordinates tan θ grow without bound towards 90°.
constexpr double kMaxPoseAngleRad = 75.0 * M_PI / 180.0;
constexpr int kMinPoseCorners = 6;
// The focal lengths tried, as fractions of the image's longest side: from a
// 280° lens (f = side / 4.9) to a 37° one.
constexpr double kLowestF = 0.2, kHighestF = 1.5;
constexpr int kGridSteps = 48;
constexpr int kGoldenSteps = 40;

double MedianOf(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The views' median RMS at f; +inf when fewer than half of them can be posed.
double MedianRms(const std::vector<const BoardObservation*>& views, double f, const cv::Point2d& centre) {
  std::vector<double> rms;
  for (const BoardObservation* view : views) {
    const double value = EquidistantViewRms(*view, f, centre);
    if (std::isfinite(value)) rms.push_back(value);
  }
  if (rms.empty() || 2 * rms.size() < views.size()) return std::numeric_limits<double>::infinity();
  return MedianOf(rms);
}

}  // namespace

double EquidistantViewRms(const BoardObservation& view, double f, const cv::Point2d& centre) {
  std::vector<cv::Point3d> object, posed_object;
  std::vector<cv::Point2d> image, rays_on_plane;
  for (size_t i = 0; i < view.image_points.size(); ++i) {
    const Eigen::Vector3d& p = view.target_points[i];
    const cv::Point2d offset(view.image_points[i].x() - centre.x, view.image_points[i].y() - centre.y);
    object.emplace_back(p.x(), p.y(), p.z());
    image.emplace_back(view.image_points[i].x(), view.image_points[i].y());
    const double r = std::hypot(offset.x, offset.y), theta = r / f;  // equidistant: r = f θ
    if (theta >= kMaxPoseAngleRad) continue;
    const double scale = r > 0 ? std::tan(theta) / r : 1.0 / f;
    posed_object.push_back(object.back());
    rays_on_plane.emplace_back(scale * offset.x, scale * offset.y);
  }
  if (static_cast<int>(posed_object.size()) < kMinPoseCorners) return std::numeric_limits<double>::infinity();
  cv::Mat rvec, tvec;
  try {
    if (!cv::solvePnP(posed_object, rays_on_plane, cv::Matx33d::eye(), cv::noArray(), rvec, tvec, false,
                      cv::SOLVEPNP_IPPE)) {
      return std::numeric_limits<double>::infinity();
    }
    cv::solvePnPRefineLM(posed_object, rays_on_plane, cv::Matx33d::eye(), cv::noArray(), rvec, tvec);
    std::vector<cv::Point2d> projected;
    const cv::Matx33d k(f, 0, centre.x, 0, f, centre.y, 0, 0, 1);
    cv::fisheye::projectPoints(object, projected, rvec, tvec, k, cv::Vec4d::all(0));
    double sum = 0;
    for (size_t i = 0; i < image.size(); ++i) {
      const cv::Point2d e = projected[i] - image[i];
      sum += e.dot(e);
    }
    return std::sqrt(sum / static_cast<double>(image.size()));
  } catch (const cv::Exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

std::optional<FisheyeStart> EquidistantStart(const std::vector<const BoardObservation*>& views, cv::Size size) {
  const cv::Point2d centre(0.5 * (size.width - 1), 0.5 * (size.height - 1));
  const double side = std::max(size.width, size.height);
  const double ratio = std::pow(kHighestF / kLowestF, 1.0 / (kGridSteps - 1));
  std::vector<double> trial_f, score;
  for (int i = 0; i < kGridSteps; ++i) {
    trial_f.push_back(kLowestF * side * std::pow(ratio, i));
    score.push_back(MedianRms(views, trial_f.back(), centre));
  }
  const size_t best = static_cast<size_t>(std::min_element(score.begin(), score.end()) - score.begin());
  if (!std::isfinite(score[best])) return std::nullopt;
  // Golden-section search between the best trial's neighbours.
  double low = trial_f[best > 0 ? best - 1 : best], high = trial_f[std::min(best + 1, trial_f.size() - 1)];
  // Each step keeps one of its two inner points, so one new median is computed.
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  double a = high - golden * (high - low), b = low + golden * (high - low);
  double at_a = MedianRms(views, a, centre), at_b = MedianRms(views, b, centre);
  for (int step = 0; step < kGoldenSteps; ++step) {
    if (at_a < at_b) {
      high = b;
      b = a;
      at_b = at_a;
      a = high - golden * (high - low);
      at_a = MedianRms(views, a, centre);
    } else {
      low = a;
      a = b;
      at_a = at_b;
      b = low + golden * (high - low);
      at_b = MedianRms(views, b, centre);
    }
  }
  FisheyeStart start;
  start.f = 0.5 * (low + high);
  start.cx = centre.x;
  start.cy = centre.y;
  start.median_rms_px = MedianRms(views, start.f, centre);
  if (!std::isfinite(start.median_rms_px) || start.median_rms_px > score[best]) {
    start.f = trial_f[best];
    start.median_rms_px = score[best];
  }
  return start;
}

}  // namespace hexcal

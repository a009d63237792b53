#include "vision/renderer.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cassert>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace hexcal {
namespace {

// SplitMix64's mixing of (seed, index) into an independent stream seed.
uint64_t StreamSeed(uint64_t seed, uint64_t index) {
  StableRandom mix(seed ^ (0x9E3779B97F4A7C15ULL * (index + 1)));
  mix.Next();
  return mix.Next();
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An occluder: a dark convex quadrilateral across part of the target's image.
std::vector<cv::Point2d> RandomOccluder(StableRandom& random, const std::vector<ProjectedCorner>& corners) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const ProjectedCorner& c : corners) {
    if (!c.visible) continue;
    lo = lo.cwiseMin(c.pixel);
    hi = hi.cwiseMax(c.pixel);
  }
  if (lo.x() > hi.x()) return {};
  // A bar from one side of the target's bounding box into it, like an arm or a cable.
  const Eigen::Vector2d size = hi - lo;
  const Eigen::Vector2d centre(random.Uniform(lo.x(), hi.x()), random.Uniform(lo.y(), hi.y()));
  const double angle = random.Uniform(0, kPi);
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle)), across(-along.y(), along.x());
  const double length = size.norm() * random.Uniform(0.3, 0.6);
  const double width = size.minCoeff() * random.Uniform(0.08, 0.2);
  std::vector<cv::Point2d> polygon;
  for (const auto& [a, b] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}}) {
    const Eigen::Vector2d p = centre + 0.5 * length * a * along + 0.5 * width * b * across;
    polygon.emplace_back(p.x(), p.y());
  }
  return polygon;
}

bool InsideConvex(const std::vector<cv::Point2d>& polygon, const Eigen::Vector2d& p, double margin) {
  if (polygon.empty()) return false;
  std::vector<cv::Point2f> contour;  // pointPolygonTest takes float or int points
  for (const cv::Point2d& q : polygon) contour.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  return cv::pointPolygonTest(contour, cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())), true) >
         -margin;
}

}  // namespace

uint64_t StableRandom::Next() {
  uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double StableRandom::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u1 = Uniform();
  while (u1 <= 0) u1 = Uniform();
  const double u2 = Uniform();
  const double radius = std::sqrt(-2 * std::log(u1));
  spare_ = radius * std::sin(2 * kPi * u2);
  has_spare_ = true;
  return radius * std::cos(2 * kPi * u2);
}

bool RenderOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  for (double level : {black_level, white_level, background_level}) {
    if (!(level >= 0 && level <= 255)) return fail("grey levels must be in [0, 255]");
  }
  if (!(black_level < white_level)) return fail("black_level must be darker than white_level");
  if (!(lighting_gradient >= 0 && lighting_gradient < 1)) return fail("lighting_gradient must be in [0, 1)");
  if (!(vignetting >= 0 && vignetting < 1)) return fail("vignetting must be in [0, 1)");
  if (!(blur_sigma_px >= 0 && blur_sigma_px <= 20)) return fail("blur_sigma_px must be in [0, 20]");
  if (!(noise_sigma >= 0 && noise_sigma <= 100)) return fail("noise_sigma must be in [0, 100] grey levels");
  if (!(shot_noise >= 0 && shot_noise <= 10)) return fail("shot_noise must be in [0, 10]");
  if (!(occlusion_probability >= 0 && occlusion_probability <= 1))
    return fail("occlusion_probability must be in [0, 1]");
  return true;
}

Renderer::Renderer(const Camera& camera, const Target& target, const RenderOptions& options)
    : camera_(camera), target_(target), options_(options), pattern_(target) {
  assert(camera.Validate().ok() && target.Validate().ok() && options.IsValid(nullptr));
  const int w = camera.width + 1, h = camera.height + 1;
  corner_rays_.assign(static_cast<size_t>(w) * h, Eigen::Vector2d(kNaN, kNaN));
  for (int v = 0; v < h; ++v) {
    std::optional<Eigen::Vector2d> previous;
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector2d pixel(u - 0.5, v - 0.5);
      std::optional<Eigen::Vector2d> ray = camera.Undistort(pixel, previous ? &*previous : nullptr);
      if (!ray && previous) ray = camera.Undistort(pixel);
      if (ray) corner_rays_[static_cast<size_t>(v) * w + u] = *ray;
      previous = ray;
    }
  }
}

Renderer::~Renderer() = default;

cv::Mat Renderer::RenderRadiance(const Pose& camera_from_target, const Eigen::Vector3d& lighting) const {
  const int width = camera_.width, height = camera_.height, stride = width + 1;
  // Target-plane (x, y) of each pixel corner: invert the plane-to-ray homography
  // [r1 r2 t], keeping only rays that hit the plane in front of the camera.
  Eigen::Matrix3d plane_to_ray;
  plane_to_ray << camera_from_target.rotation.col(0), camera_from_target.rotation.col(1), camera_from_target.position;
  const Eigen::Matrix3d ray_to_plane = plane_to_ray.inverse();
  std::vector<Eigen::Vector2d> on_plane(corner_rays_.size());
  for (size_t k = 0; k < corner_rays_.size(); ++k) {
    const Eigen::Vector3d p = ray_to_plane * corner_rays_[k].homogeneous();
    on_plane[k] = p.z() > 0 ? Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()) : Eigen::Vector2d(kNaN, kNaN);
  }
  const double diagonal = std::hypot(width, height);
  const Eigen::Vector2d centre(0.5 * (width - 1), 0.5 * (height - 1));
  cv::Mat radiance(height, width, CV_64F);
  for (int v = 0; v < height; ++v) {
    double* row = radiance.ptr<double>(v);
    for (int u = 0; u < width; ++u) {
      const size_t k = static_cast<size_t>(v) * stride + u;
      const std::array<Eigen::Vector2d, 4> quad = {on_plane[k], on_plane[k + 1], on_plane[k + stride + 1],
                                                   on_plane[k + stride]};
      double level = options_.background_level;
      if (quad[0].allFinite() && quad[1].allFinite() && quad[2].allFinite() && quad[3].allFinite()) {
        const TargetPattern::Coverage c = pattern_.Cover(quad);
        level = options_.background_level * (1 - c.sheet) + options_.white_level * (c.sheet - c.black) +
                options_.black_level * c.black;
      }
      // Illumination: a linear ramp in a random direction times a cos⁴-like falloff.
      const Eigen::Vector2d d = (Eigen::Vector2d(u, v) - centre) / diagonal;
      const double ramp = 1 + lighting.z() * (lighting.x() * d.x() + lighting.y() * d.y());
      const double falloff = 1 - options_.vignetting * 4 * d.squaredNorm();
      row[u] = level * ramp * falloff;
    }
  }
  return radiance;
}

RenderedView Renderer::Render(const Pose& camera_from_target, uint64_t image_index) const {
  StableRandom random(StreamSeed(options_.seed, image_index));
  RenderedView view;
  view.camera_from_target = camera_from_target;
  for (int index = 0; index < target_.NumTags(); ++index) {
    const int id = target_.TagId(index);
    const std::array<Eigen::Vector3d, 4> corners = target_.TagCorners(id);
    for (int k = 0; k < 4; ++k) {
      ProjectedCorner corner;
      corner.tag_id = id;
      corner.corner = k;
      const Eigen::Vector3d p = camera_from_target * corners[static_cast<size_t>(k)];
      if (p.z() > 0) {
        corner.pixel = camera_.Project(p);
        // Inside the image with room for the detector's edge fit.
        corner.visible = corner.pixel.x() >= 2 && corner.pixel.y() >= 2 && corner.pixel.x() <= camera_.width - 3 &&
                         corner.pixel.y() <= camera_.height - 3;
      }
      view.corners.push_back(corner);
    }
  }
  const double angle = random.Uniform(0, 2 * kPi);
  const Eigen::Vector3d lighting(std::cos(angle), std::sin(angle), options_.lighting_gradient);
  cv::Mat radiance = RenderRadiance(camera_from_target, lighting);

  const bool occluded = random.Uniform() < options_.occlusion_probability;
  if (occluded) {
    const std::vector<cv::Point2d> polygon = RandomOccluder(random, view.corners);
    if (!polygon.empty()) {
      // Anti-aliased: drawn 4× larger and averaged down.
      constexpr int kScale = 4;
      cv::Mat mask(radiance.rows * kScale, radiance.cols * kScale, CV_8U, cv::Scalar(0));
      std::vector<cv::Point> scaled;
      for (const cv::Point2d& p : polygon)
        scaled.emplace_back(cvRound((p.x + 0.5) * kScale), cvRound((p.y + 0.5) * kScale));
      cv::fillConvexPoly(mask, scaled, cv::Scalar(255));
      cv::Mat coverage;
      cv::resize(mask, coverage, radiance.size(), 0, 0, cv::INTER_AREA);
      coverage.convertTo(coverage, CV_64F, 1.0 / 255);
      const double occluder_level = 0.5 * (options_.black_level + options_.background_level);
      radiance = radiance.mul(1 - coverage) + occluder_level * coverage;
      for (ProjectedCorner& c : view.corners) {
        if (c.visible && InsideConvex(polygon, c.pixel, 3.0)) c.visible = false;
      }
    }
  }
  if (options_.blur_sigma_px > 0) {
    cv::GaussianBlur(radiance, radiance, cv::Size(0, 0), options_.blur_sigma_px, options_.blur_sigma_px,
                     cv::BORDER_REFLECT);
  }
  view.image.create(radiance.size(), CV_8U);
  for (int v = 0; v < radiance.rows; ++v) {
    const double* in = radiance.ptr<double>(v);
    uint8_t* out = view.image.ptr<uint8_t>(v);
    for (int u = 0; u < radiance.cols; ++u) {
      const double sigma =
          std::sqrt(options_.noise_sigma * options_.noise_sigma + options_.shot_noise * std::max(0.0, in[u]));
      const double value = in[u] + sigma * random.Normal();
      out[u] = static_cast<uint8_t>(std::clamp(std::lround(value), 0L, 255L));
    }
  }
  return view;
}

std::vector<Pose> RandomViewPoses(const Target& target, int count, double distance_min, double distance_max,
                                  double max_tilt_deg, double max_roll_deg, double max_offset, uint64_t seed) {
  StableRandom random(StreamSeed(seed, 0xC0FFEE));
  const Eigen::Vector2d middle = target.TagsMin() + 0.5 * Eigen::Vector2d(target.Width(), target.Height());
  const Eigen::Vector3d centre(middle.x(), middle.y(), 0);
  // Fronto-parallel and upright: camera x = target x, camera y = -target y.
  const Eigen::Matrix3d upright = Eigen::Vector3d(1, -1, -1).asDiagonal();
  std::vector<Pose> poses;
  for (int i = 0; i < count; ++i) {
    const double distance = random.Uniform(distance_min, distance_max);
    const double tilt = DegToRad(max_tilt_deg) * std::sqrt(random.Uniform());
    const double tilt_axis = random.Uniform(0, 2 * kPi);
    const double roll = DegToRad(random.Uniform(-max_roll_deg, max_roll_deg));
    const Eigen::Matrix3d tilt_rotation =
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(tilt_axis), std::sin(tilt_axis), 0)).toRotationMatrix();
    Pose pose;
    pose.rotation = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix() * upright * tilt_rotation;
    const Eigen::Vector3d centre_in_camera(distance * random.Uniform(-max_offset, max_offset),
                                           distance * random.Uniform(-max_offset, max_offset), distance);
    pose.position = centre_in_camera - pose.rotation * centre;
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace hexcal

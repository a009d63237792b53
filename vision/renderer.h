// Synthetic images of the target: the ground truth for tests, benchmarks and
// the demo. Each pixel is the exact area-average of the printed pattern over
// the pixel's footprint on the target plane (through the lens distortion),
// then uneven lighting, optical blur and sensor noise are applied:
//
//   radiance  = level(black / white sheet / background) · illumination(u, v)
//   image     = GaussianBlur(radiance, blur_sigma_px)
//             + N(0, noise_sigma² + shot_noise · image)     , rounded to 8 bits
//
// Pixels follow OpenCV's convention: pixel (u, v) covers [u-½, u+½] × [v-½, v+½].
// The same options, seed and index give the same image, bit for bit, on any
// thread.
//
//   Renderer renderer(SimulatedCamera(), DefaultTarget(), RenderOptions{});
//   RenderedView view = renderer.Render(camera_from_target, /*image_index=*/0);
//   cv::imwrite("view.png", view.image);
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/pose.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "vision/target_coverage.h"

namespace hexcal {

struct RenderOptions {
  double black_level = 28;           // grey level of black ink under unit illumination
  double white_level = 205;          // grey level of the white sheet
  double background_level = 70;      // grey level around the sheet
  double lighting_gradient = 0.3;    // illumination change across the image diagonal, relative; random direction
  double vignetting = 0.25;          // relative darkening at the image corners
  double blur_sigma_px = 0.7;        // optical blur, Gaussian sigma in pixels (0 = none)
  double noise_sigma = 1.5;          // read noise, grey levels
  double shot_noise = 0.02;          // photon noise variance per grey level of signal
  double occlusion_probability = 0;  // chance that an image has an occluder over the target
  uint64_t seed = 1;

  bool IsValid(std::string* error) const;
};

// A corner of the target as the camera sees it.
struct ProjectedCorner {
  int tag_id = 0;
  int corner = 0;  // 0..3, AprilTag order
  // With distortion, OpenCV convention; NaN when behind the camera.
  Eigen::Vector2d pixel = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  bool visible = false;  // in front, inside the image, not occluded
};

struct RenderedView {
  cv::Mat image;  // CV_8UC1, camera width × height
  Pose camera_from_target;
  std::vector<ProjectedCorner> corners;  // every corner of every tag
};

class Renderer {
 public:
  // camera and target must be valid (asserted by their Validate()).
  Renderer(const Camera& camera, const Target& target, const RenderOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Thread-safe: the per-image random stream depends on (seed, image_index) only.
  RenderedView Render(const Pose& camera_from_target, uint64_t image_index) const;

  const Camera& camera() const { return camera_; }
  const Target& target() const { return target_; }

 private:
  cv::Mat RenderRadiance(const Pose& camera_from_target, const Eigen::Vector3d& lighting) const;

  Camera camera_;
  Target target_;
  RenderOptions options_;
  TargetPattern pattern_;
  // Normalised undistorted rays of the pixel corners (u - ½, v - ½), (W+1) × (H+1);
  // NaN where the distortion model does not invert.
  std::vector<Eigen::Vector2d> corner_rays_;
};

// Poses camera_from_target that look at the target's centre from `distance`
// (length unit of the target) with random tilt up to `max_tilt_deg` and
// in-plane rotation up to `max_roll_deg`, the centre shifted in the image by
// up to `max_offset` (fraction of the distance). Deterministic in `seed`.
std::vector<Pose> RandomViewPoses(const Target& target, int count, double distance_min, double distance_max,
                                  double max_tilt_deg, double max_roll_deg, double max_offset, uint64_t seed);

// A deterministic uniform [0, 1) generator with a stable sequence on every
// platform (SplitMix64), and standard normals by Box–Muller.
class StableRandom {
 public:
  explicit StableRandom(uint64_t seed) : state_(seed) {}
  uint64_t Next();
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  double Normal();

 private:
  uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0;
};

}  // namespace hexcal

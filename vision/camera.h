// The camera models: a pinhole (fx, fy, cx, cy, no skew) with one of three
// lens distortions, and their files.
//
// Camera frame (OpenCV): origin at the optical centre, x right, y down, z along
// the optical axis. Pixel coordinates: OpenCV's convention, (0, 0) is the
// centre of the top-left pixel (docs/conventions.md). For a point p in the
// camera frame, x = p.x/p.z, y = p.y/p.z, r² = x² + y², and
//   u = fx x_d + cx,  v = fy y_d + cy
// with (x_d, y_d) the distorted normalised coordinates of the model:
//
// kRadTan (OpenCV's 5 coefficients k1 k2 p1 p2 k3, ROS plumb_bob, Kalibr radtan):
//   x_d = x (1 + k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 x y + p2 (r² + 2 x²)
//   y_d = y (1 + k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2 y²) + 2 p2 x y
// kRational (OpenCV's CALIB_RATIONAL_MODEL, k1 k2 p1 p2 k3 k4 k5 k6, ROS
// rational_polynomial): the radial factor above becomes
//   (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
// kPinholeEqui (equidistant fisheye: cv::fisheye, Kalibr pinhole-equi, ROS
// equidistant; k1 k2 k3 k4):
//   θ = atan(r),  θ_d = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸),  (x_d, y_d) = (θ_d / r) (x, y)
//   (Project uses θ = atan2(|p.xy|, p.z), the same for p.z > 0.)
//
// Files, read and written (CameraToText): OpenCV FileStorage YAML as OpenCV's
// calibration sample writes it (camera_matrix, distortion_coefficients,
// image_width, image_height; 8 coefficients are the rational model,
// `distortion_model: equidistant` marks a fisheye), ROS camera_info YAML
// (distortion_model plumb_bob, rational_polynomial or equidistant), or a
// Kalibr camchain YAML (cam0: camera_model pinhole, distortion_model radtan
// or equidistant).
//
//   StatusOr<Camera> camera = LoadCamera("camera.yaml");
//   Eigen::Vector2d pixel = camera->Project(p_in_camera);
//   std::optional<Eigen::Vector2d> ray = camera->Undistort(pixel);  // normalised x, y
//   StatusOr<std::string> ros = CameraToText(*camera, CameraFileFormat::kRos);
#pragma once

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"

namespace hexcal {

enum class CameraModel {
  kRadTan,       // OpenCV's k1 k2 p1 p2 k3 (the default)
  kRational,     // OpenCV's k1 k2 p1 p2 k3 k4 k5 k6 (CALIB_RATIONAL_MODEL)
  kPinholeEqui,  // equidistant fisheye k1 k2 k3 k4 (cv::fisheye, Kalibr pinhole-equi)
};

// "radtan", "rational", "pinhole-equi" (the names of `intrinsics --model`).
const char* CameraModelName(CameraModel model);
std::optional<CameraModel> CameraModelFromName(const std::string& name);

struct Camera {
  int width = 0;                             // pixels
  int height = 0;                            // pixels
  double fx = 0, fy = 0;                     // focal lengths, pixels
  double cx = 0, cy = 0;                     // principal point, pixels (OpenCV convention)
  CameraModel model = CameraModel::kRadTan;  // which distortion `distortion` holds
  std::array<double, 8> distortion = {};     // the model's coefficients in its order (above); unused ones 0

  cv::Matx33d CameraMatrix() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
  // The model's coefficients, CV_64F: 1×5 (kRadTan), 1×8 (kRational, for
  // OpenCV's functions) or 1×4 (kPinholeEqui, for cv::fisheye only).
  cv::Mat DistortionCoefficients() const;
  int NumCoefficients() const;  // 5, 8 or 4
  // "fx", "fy", "cx", "cy" then the model's coefficients ("k1", "k2", "p1", ...).
  std::vector<std::string> ParameterNames() const;
  std::vector<double> ParameterValues() const;  // in the order of ParameterNames

  // Normalised, undistorted (x, y) -> distorted normalised coordinates.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy) const;
  // Pixel of a point in the camera frame (z > 0), with distortion.
  Eigen::Vector2d Project(const Eigen::Vector3d& p_in_camera) const;
  // Normalised undistorted (x, y) of a pixel: Newton's method on Distort, to
  // 1e-12; nullopt where the model does not invert (far outside the image).
  // `start`: a first guess, e.g. the answer for a neighbouring pixel. The
  // fisheye solves θ_d(θ) = |(x_d, y_d)| for θ on the branch where θ_d grows
  // (bracketed Newton); nullopt past it or at θ ≥ 90°.
  std::optional<Eigen::Vector2d> Undistort(const Eigen::Vector2d& pixel, const Eigen::Vector2d* start = nullptr) const;
  // The pixel an ideal (distortion-free) camera with the same fx, fy, cx, cy sees.
  std::optional<Eigen::Vector2d> IdealPixel(const Eigen::Vector2d& pixel) const;
  // Inverse of IdealPixel.
  Eigen::Vector2d DistortedPixel(const Eigen::Vector2d& ideal_pixel) const;
  // The angle (radians) between the optical axis and the ray a pixel sees:
  // atan |Undistort(pixel)|, and for the fisheye θ itself, so past 90° too, up
  // to 180° (on the branch where θ_d grows); nullopt where the model does not invert.
  std::optional<double> OffAxisAngle(const Eigen::Vector2d& pixel) const;

  // Finite values, a positive size within kMaxImagePixels and the ranges below.
  Status Validate() const;

 private:
  Status ValidateRanges() const;
};

// Plausible camera values (Camera::Validate): far beyond any real lens and
// sensor, so that only a typo or a wrong unit meets them.
constexpr double kMinFocalPixels = 0.01;           // fx, fy
constexpr double kMaxFocalPixels = 1e7;            // fx, fy
constexpr double kMaxDistortionCoefficient = 1e6;  // |k| of every model
// cx within [-width, 2 width], cy within [-height, 2 height].

// The ideal pixel (Camera::IdealPixel) of every pixel centre of the image,
// computed once per camera: the edge fit (edge_refine.h) looks it up for
// every pixel it uses. NaN where the model does not invert.
class IdealPixelMap {
 public:
  explicit IdealPixelMap(const Camera& camera);
  int width() const { return width_; }
  int height() const { return height_; }
  // (u, v) inside the image.
  Eigen::Vector2d At(int u, int v) const {
    const size_t k = 2 * (static_cast<size_t>(v) * width_ + u);
    return {xy_[k], xy_[k + 1]};
  }
  const Camera& camera() const { return camera_; }

 private:
  Camera camera_;
  int width_ = 0, height_ = 0;
  std::vector<float> xy_;  // float: 1e-4 px at 1000 px, 4× under the fit's noise floor
};

// The angles the image spans, in degrees, each the sum of the off-axis angles
// (Camera::OffAxisAngle) of two opposite points of the image's outer edge:
// horizontal through the principal point's row (u = -0.5 and width - 0.5,
// pixel centres at whole numbers), vertical through its column, diagonal
// through the top-left and bottom-right corners. nullopt where a point is past
// what the model inverts (a strong fisheye's corners, say).
struct FieldOfView {
  std::optional<double> horizontal_deg, vertical_deg, diagonal_deg;
};
FieldOfView CameraFieldOfView(const Camera& camera);

// What a calibration adds to a camera file (all optional).
struct CameraFileExtras {
  std::string calibration_time;         // "2026-11-22 10:03:00"
  int views = 0;                        // nr_of_frames
  double rms_px = -1;                   // avg_reprojection_error; < 0: not written
  std::vector<double> std_dev;          // in the order of Camera::ParameterNames(); empty: none
  std::vector<double> per_view_rms_px;  // per_view_reprojection_errors
  std::string comment;                  // written as '#' lines at the top
};

// OpenCV FileStorage YAML text (%YAML:1.0, !!opencv-matrix); numbers in the
// shortest form that reads back exactly. The model's coefficients (5, 8 or 4),
// and `distortion_model: rational_polynomial | equidistant` for the models
// other than kRadTan (whose file is exactly what OpenCV's sample writes).
std::string CameraToOpenCvYaml(const Camera& camera, const CameraFileExtras& extras = {});
Status SaveCamera(const Camera& camera, const std::string& path, const CameraFileExtras& extras = {});

// The formats hexcal writes a camera in (camera_writers.cc); ParseCameraFile
// reads all three back to the same camera, bit for bit.
enum class CameraFileFormat {
  kOpenCv,  // CameraToOpenCvYaml
  kRos,     // CameraToRosYaml
  kKalibr,  // CameraToKalibrYaml
};
const char* CameraFileFormatName(CameraFileFormat format);  // "opencv", "ros", "kalibr"
std::optional<CameraFileFormat> CameraFileFormatFromName(const std::string& name);

// ROS camera_info YAML, as camera_calibration_parsers writes it: image_width,
// image_height, camera_name, camera_matrix, distortion_model (plumb_bob,
// rational_polynomial, equidistant), distortion_coefficients, an identity
// rectification_matrix and projection_matrix [K | 0] (a monocular camera
// whose rectified image keeps fx fy cx cy). Every real number has a '.' (and
// its exponent, if any, a sign), so that PyYAML, which ROS's Python tools read
// with, takes it for a float: it reads "1e-05" as a string, "903" as an int. `camera_name`: letters,
// digits and '_' (IsRosCameraName), as camera_info_manager requires.
std::string CameraToRosYaml(const Camera& camera, const std::string& camera_name = "camera");
bool IsRosCameraName(const std::string& name);
// A Kalibr camchain of one camera (cam0: camera_model pinhole, intrinsics
// [fu, fv, pu, pv], distortion_model radtan | equidistant, distortion_coeffs,
// resolution [w, h]), numbers as for ROS (Kalibr also wants fu, fv, pu, pv
// as floats). Refused, naming the model or the coefficient, for what Kalibr
// cannot hold: the rational model, radtan with k3 ≠ 0 (Kalibr's radtan is
// k1 k2 p1 p2), a principal point Kalibr's reader rejects (negative).
StatusOr<std::string> CameraToKalibrYaml(const Camera& camera);
// The file text in `format`; `ros_camera_name` is checked and used for kRos only.
StatusOr<std::string> CameraToText(const Camera& camera, CameraFileFormat format,
                                   const std::string& ros_camera_name = "camera");

// OpenCV FileStorage YAML (read with yaml-cpp) or XML (cv::FileStorage),
// recognised by its "%YAML:1." or "<?xml" header; else a Kalibr camchain
// (a `cam0` key, or `camera_model` / `intrinsics` at the top level; of several
// cameras cam0 is read, a camchain without cam0 is refused) or ROS camera_info YAML. Messages read
// "camera file '<path>': <key>: <problem>" and never quote the file beyond a short value.
StatusOr<Camera> ParseCameraFile(const std::string& text, const std::string& source);
// A file, or the name "sim-4.2mm-1024x768" (SimulatedCamera) when no such file exists.
StatusOr<Camera> LoadCamera(const std::string& path_or_name);

// The simulated camera of the tests and benchmarks: 1024 × 768, 4.65 µm
// pixels behind a 4.2 mm lens (f = 903.2 px), moderate barrel distortion.
// Also resources/cameras/sim-4.2mm-1024x768.yaml.
Camera SimulatedCamera();
constexpr const char* kSimulatedCameraName = "sim-4.2mm-1024x768";
// The tests' fisheye: the same 1024 × 768 sensor and principal point behind an
// equidistant lens (f ≈ 520 px) that sees 70° off axis in the image corners.
Camera SimulatedFisheyeCamera();

}  // namespace hexcal

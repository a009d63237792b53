// The camera models' maths (camera.h); their files are in camera_file.cc.
#include "vision/camera.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "core/csv.h"
#include "vision/image_header.h"

namespace hexcal {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// The radial factor of kRadTan / kRational and its derivative by r²:
// a / b with a = 1 + k1 r² + k2 r⁴ + k3 r⁶, b = 1 + k4 r² + k5 r⁴ + k6 r⁶
// (b = 1 for kRadTan, which makes both exactly the plain polynomial's).
struct Radial {
  double factor, derivative;
};

Radial RadialFactor(const Camera& camera, double r2) {
  const auto& d = camera.distortion;
  const bool rational = camera.model == CameraModel::kRational;
  const double k4 = rational ? d[5] : 0, k5 = rational ? d[6] : 0, k6 = rational ? d[7] : 0;
  const double a = 1 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  const double b = 1 + r2 * (k4 + r2 * (k5 + r2 * k6));
  const double a_d = d[0] + r2 * (2 * d[1] + 3 * d[4] * r2);
  const double b_d = k4 + r2 * (2 * k5 + 3 * k6 * r2);
  const double factor = a / b;
  return {factor, (a_d - factor * b_d) / b};
}

// d(x_d, y_d)/d(x, y) of the radial-tangential models in camera.h.
Eigen::Matrix2d DistortionJacobian(const Camera& camera, const Eigen::Vector2d& xy) {
  const double p1 = camera.distortion[2], p2 = camera.distortion[3];
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const auto [radial, radial_d] = RadialFactor(camera, r2);  // radial_d: d radial / d r²
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2 * x * x * radial_d + 2 * p1 * y + 6 * p2 * x;
  j(0, 1) = 2 * x * y * radial_d + 2 * p1 * x + 2 * p2 * y;
  j(1, 0) = 2 * x * y * radial_d + 2 * p1 * x + 2 * p2 * y;
  j(1, 1) = radial + 2 * y * y * radial_d + 6 * p1 * y + 2 * p2 * x;
  return j;
}

// θ_d(θ) of the equidistant model and its derivative.
double FisheyeThetaD(const std::array<double, 8>& k, double theta) {
  const double t2 = theta * theta;
  return theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
}

double FisheyeThetaDSlope(const std::array<double, 8>& k, double theta) {
  const double t2 = theta * theta;
  return 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
}

// The end of the branch where θ_d grows from θ = 0: the first zero of its
// slope in (0, max_theta], else max_theta (sampled at max_theta / 64 steps,
// 1.4° for π/2, then bisected).
double FisheyeMonotoneLimit(const std::array<double, 8>& k, double max_theta) {
  constexpr int kSamples = 64;
  double previous = 0;
  for (int i = 1; i <= kSamples; ++i) {
    const double theta = max_theta * i / kSamples;
    if (FisheyeThetaDSlope(k, theta) > 0) {
      previous = theta;
      continue;
    }
    double lo = previous, hi = theta;
    for (int step = 0; step < 60; ++step) {
      const double mid = 0.5 * (lo + hi);
      (FisheyeThetaDSlope(k, mid) > 0 ? lo : hi) = mid;
    }
    return lo;
  }
  return max_theta;
}

// θ of the fisheye from θ_d(θ) = theta_d (> 0) by Newton kept inside a
// bracket (bisection when a step leaves it), on [0, FisheyeMonotoneLimit];
// nullopt past that branch or at max_theta and beyond. `theta` starts the
// search (ignored outside the bracket).
std::optional<double> FisheyeTheta(const std::array<double, 8>& k, double theta_d, double theta, double max_theta) {
  double lo = 0, hi = FisheyeMonotoneLimit(k, max_theta);
  if (!(FisheyeThetaD(k, hi) > theta_d)) return std::nullopt;
  if (!(theta > lo && theta < hi)) theta = theta_d < hi ? theta_d : 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = FisheyeThetaD(k, theta) - theta_d;
    if (f == 0) break;
    (f < 0 ? lo : hi) = theta;
    double next = theta - f / FisheyeThetaDSlope(k, theta);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - theta) <= 4 * std::numeric_limits<double>::epsilon() * theta;
    theta = next;
    if (converged) break;
  }
  return theta;
}

// Normalised undistorted (x, y) of distorted normalised `target` for the
// fisheye (FisheyeTheta); nullopt at 90° and beyond, where there is no (x, y).
std::optional<Eigen::Vector2d> UndistortFisheye(const Camera& camera, const Eigen::Vector2d& target,
                                                const Eigen::Vector2d* start) {
  const double theta_d = target.norm();
  if (!std::isfinite(theta_d)) return std::nullopt;
  if (theta_d == 0) return Eigen::Vector2d(0, 0);
  const std::optional<double> solved =
      FisheyeTheta(camera.distortion, theta_d, start ? std::atan(start->norm()) : theta_d, kHalfPi);
  if (!solved || !(*solved < kHalfPi)) return std::nullopt;
  const double theta = *solved;
  const Eigen::Vector2d xy = target * (std::tan(theta) / theta_d);
  if (!xy.allFinite() || !((camera.Distort(xy) - target).norm() <= 1e-11 * std::max(1.0, theta_d))) return std::nullopt;
  return xy;
}

}  // namespace

const char* CameraModelName(CameraModel model) {
  switch (model) {
    case CameraModel::kRadTan:
      return "radtan";
    case CameraModel::kRational:
      return "rational";
    case CameraModel::kPinholeEqui:
      return "pinhole-equi";
  }
  return "unknown";
}

std::optional<CameraModel> CameraModelFromName(const std::string& name) {
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui}) {
    if (name == CameraModelName(model)) return model;
  }
  return std::nullopt;
}

int Camera::NumCoefficients() const {
  switch (model) {
    case CameraModel::kRational:
      return 8;
    case CameraModel::kPinholeEqui:
      return 4;
    case CameraModel::kRadTan:
      break;
  }
  return 5;
}

cv::Mat Camera::DistortionCoefficients() const {
  cv::Mat d(1, NumCoefficients(), CV_64F);
  for (int i = 0; i < d.cols; ++i) d.at<double>(0, i) = distortion[static_cast<size_t>(i)];
  return d;
}

std::vector<std::string> Camera::ParameterNames() const {
  std::vector<std::string> names = {"fx", "fy", "cx", "cy"};
  if (model == CameraModel::kPinholeEqui) {
    names.insert(names.end(), {"k1", "k2", "k3", "k4"});
  } else {
    names.insert(names.end(), {"k1", "k2", "p1", "p2", "k3"});
    if (model == CameraModel::kRational) names.insert(names.end(), {"k4", "k5", "k6"});
  }
  return names;
}

std::vector<double> Camera::ParameterValues() const {
  std::vector<double> values = {fx, fy, cx, cy};
  values.insert(values.end(), distortion.begin(), distortion.begin() + NumCoefficients());
  return values;
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& xy) const {
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  if (model == CameraModel::kPinholeEqui) {
    const double r = std::sqrt(r2);
    return r > 0 ? Eigen::Vector2d(xy * (FisheyeThetaD(distortion, std::atan(r)) / r)) : xy;
  }
  const double p1 = distortion[2], p2 = distortion[3];
  const double radial = RadialFactor(*this, r2).factor;
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

Eigen::Vector2d Camera::Project(const Eigen::Vector3d& p_in_camera) const {
  Eigen::Vector2d d;
  if (model == CameraModel::kPinholeEqui) {
    // θ from atan2, so that rays at and beyond 90° still have a pixel.
    const double r = p_in_camera.head<2>().norm();
    const double theta_d = FisheyeThetaD(distortion, std::atan2(r, p_in_camera.z()));
    d = r > 0 ? Eigen::Vector2d(p_in_camera.head<2>() * (theta_d / r)) : Eigen::Vector2d(0, 0);
  } else {
    d = Distort(p_in_camera.head<2>() / p_in_camera.z());
  }
  return {fx * d.x() + cx, fy * d.y() + cy};
}

std::optional<Eigen::Vector2d> Camera::Undistort(const Eigen::Vector2d& pixel, const Eigen::Vector2d* start) const {
  const Eigen::Vector2d target((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  if (model == CameraModel::kPinholeEqui) return UndistortFisheye(*this, target, start);
  Eigen::Vector2d xy = start ? *start : target;
  double error = (Distort(xy) - target).norm();
  for (int iteration = 0; iteration < 50 && error > 1e-13; ++iteration) {
    const Eigen::Matrix2d j = DistortionJacobian(*this, xy);
    if (!(j.determinant() > 0)) return std::nullopt;
    const Eigen::Vector2d step = j.inverse() * (target - Distort(xy));
    // Damped: halve the step until the residual drops.
    double scale = 1;
    Eigen::Vector2d next = xy + step;
    double next_error = (Distort(next) - target).norm();
    while (next_error >= error && scale > 1e-6) {
      scale *= 0.5;
      next = xy + scale * step;
      next_error = (Distort(next) - target).norm();
    }
    if (next_error >= error) break;
    xy = next;
    error = next_error;
  }
  if (!(error <= 1e-11) || !(DistortionJacobian(*this, xy).determinant() > 0)) return std::nullopt;
  return xy;
}

std::optional<Eigen::Vector2d> Camera::IdealPixel(const Eigen::Vector2d& pixel) const {
  const std::optional<Eigen::Vector2d> xy = Undistort(pixel);
  if (!xy) return std::nullopt;
  return Eigen::Vector2d(fx * xy->x() + cx, fy * xy->y() + cy);
}

Eigen::Vector2d Camera::DistortedPixel(const Eigen::Vector2d& ideal_pixel) const {
  const Eigen::Vector2d d = Distort({(ideal_pixel.x() - cx) / fx, (ideal_pixel.y() - cy) / fy});
  return {fx * d.x() + cx, fy * d.y() + cy};
}

std::optional<double> Camera::OffAxisAngle(const Eigen::Vector2d& pixel) const {
  if (model != CameraModel::kPinholeEqui) {
    const std::optional<Eigen::Vector2d> xy = Undistort(pixel);
    if (!xy) return std::nullopt;
    return std::atan(xy->norm());
  }
  const double theta_d = Eigen::Vector2d((pixel.x() - cx) / fx, (pixel.y() - cy) / fy).norm();
  if (!std::isfinite(theta_d)) return std::nullopt;
  if (theta_d == 0) return 0.0;
  // Up to 180°: Project takes θ = atan2(|p.xy|, p.z), so rays behind the image plane have pixels too.
  const std::optional<double> theta = FisheyeTheta(distortion, theta_d, theta_d, 2 * kHalfPi);
  // The same check as UndistortFisheye's: the angle must give the pixel back.
  if (!theta || !(std::abs(FisheyeThetaD(distortion, *theta) - theta_d) <= 1e-11 * std::max(1.0, theta_d)))
    return std::nullopt;
  return theta;
}

FieldOfView CameraFieldOfView(const Camera& camera) {
  // Pixel centres are whole numbers (docs/conventions.md): the image's outer
  // edge is half a pixel beyond the first and last centres.
  const double left = -0.5, top = -0.5, right = camera.width - 0.5, bottom = camera.height - 0.5;
  const auto span = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) -> std::optional<double> {
    const std::optional<double> angle_a = camera.OffAxisAngle(a), angle_b = camera.OffAxisAngle(b);
    if (!angle_a || !angle_b) return std::nullopt;
    return (*angle_a + *angle_b) * (90.0 / kHalfPi);
  };
  return {span({left, camera.cy}, {right, camera.cy}), span({camera.cx, top}, {camera.cx, bottom}),
          span({left, top}, {right, bottom})};
}

Status Camera::Validate() const {
  if (width <= 0 || height <= 0) {
    return Status::BadInput("image size " + std::to_string(width) + " x " + std::to_string(height) +
                            ": must be positive");
  }
  // No image hexcal reads is larger (image_header.h): a camera of 10^6 x 10^6
  // pixels made acquire allocate 4 TB and abort with std::bad_alloc (issue 36).
  if (static_cast<uint64_t>(width) * static_cast<uint64_t>(height) > kMaxImagePixels) {
    return Status::BadInput("image size " + std::to_string(width) + " x " + std::to_string(height) + ": over the " +
                            std::to_string(kMaxImagePixels / 1'000'000) + "-megapixel limit of an image hexcal reads");
  }
  for (const auto& [name, f] : {std::pair{"fx", fx}, std::pair{"fy", fy}}) {
    if (!std::isfinite(f)) return Status::BadInput(std::string("focal length ") + name + ": not a finite number");
  }
  if (!(fx > 0) || !(fy > 0)) {
    return Status::BadInput("focal lengths fx = " + FormatNumber(fx) + ", fy = " + FormatNumber(fy) +
                            ": must be positive");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) return Status::BadInput("principal point: not finite");
  for (double k : distortion) {
    if (!std::isfinite(k)) return Status::BadInput("distortion_coefficients: not finite");
  }
  for (size_t i = static_cast<size_t>(NumCoefficients()); i < distortion.size(); ++i) {
    if (distortion[i] != 0) {
      return Status::BadInput("distortion_coefficients: coefficient " + std::to_string(i + 1) + " is not 0; the " +
                              CameraModelName(model) + " model has " + std::to_string(NumCoefficients()));
    }
  }
  return ValidateRanges();
}

// Plausible values, far outside any real camera's (issue 36: a focal length of
// 1e300 or 1e-300, k1 = 1e300 or a principal point at -5000 px were accepted).
Status Camera::ValidateRanges() const {
  const auto outside = [](const std::string& key, double value, double min, double max, const std::string& unit) {
    return Status::BadInput(key + " = " + FormatNumber(value) + unit + " is outside [" + FormatNumber(min) + ", " +
                            FormatNumber(max) + "]" + unit);
  };
  for (const auto& [name, f] : {std::pair{"fx", fx}, std::pair{"fy", fy}})
    if (f < kMinFocalPixels || f > kMaxFocalPixels) return outside(name, f, kMinFocalPixels, kMaxFocalPixels, " px");
  if (cx < -width || cx > 2.0 * width) return outside("cx", cx, -width, 2.0 * width, " px");
  if (cy < -height || cy > 2.0 * height) return outside("cy", cy, -height, 2.0 * height, " px");
  for (size_t i = 0; i < distortion.size(); ++i) {
    if (std::abs(distortion[i]) > kMaxDistortionCoefficient)
      return outside("distortion coefficient " + std::to_string(i + 1), distortion[i], -kMaxDistortionCoefficient,
                     kMaxDistortionCoefficient, "");
  }
  return Status::Ok();
}

IdealPixelMap::IdealPixelMap(const Camera& camera) : camera_(camera), width_(camera.width), height_(camera.height) {
  xy_.assign(2 * static_cast<size_t>(width_) * height_, std::numeric_limits<float>::quiet_NaN());
  for (int v = 0; v < height_; ++v) {
    std::optional<Eigen::Vector2d> previous;
    for (int u = 0; u < width_; ++u) {
      std::optional<Eigen::Vector2d> xy = camera.Undistort(Eigen::Vector2d(u, v), previous ? &*previous : nullptr);
      if (!xy && previous) xy = camera.Undistort(Eigen::Vector2d(u, v));
      if (xy) {
        const size_t k = 2 * (static_cast<size_t>(v) * width_ + u);
        xy_[k] = static_cast<float>(camera.fx * xy->x() + camera.cx);
        xy_[k + 1] = static_cast<float>(camera.fy * xy->y() + camera.cy);
      }
      previous = xy;
    }
  }
}

Camera SimulatedCamera() {
  Camera camera;
  camera.width = 1024;
  camera.height = 768;
  camera.fx = camera.fy = 903.2;  // 4.2 mm / 4.65 µm
  camera.cx = 515.3;              // a few pixels off the image centre (511.5, 383.5),
  camera.cy = 380.1;              // as a real lens mount is
  camera.distortion = {-0.28, 0.09, 0.0004, -0.0003, -0.012};
  return camera;
}

Camera SimulatedFisheyeCamera() {
  Camera camera = SimulatedCamera();
  camera.model = CameraModel::kPinholeEqui;
  camera.fx = 520.4;
  camera.fy = 519.8;
  camera.distortion = {0.05, -0.02, 0.004, -0.0005};
  return camera;
}

}  // namespace hexcal

#include "core/camera_frame_residuals.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/forward_kinematics.h"

namespace hexcal {
namespace {

struct LineFit {
  double slope = 0, slope_se = 0;
};

// Least squares δ ≈ c + k·u; se(k) = s / √Σ(u − ū)², s² = Σ r² / (n − 2).
// The caller guarantees n ≥ 3 and a spread of u.
LineFit FitLine(const std::vector<double>& u, const std::vector<double>& delta) {
  const double n = static_cast<double>(u.size());
  double u_mean = 0, d_mean = 0;
  for (size_t j = 0; j < u.size(); ++j) {
    u_mean += u[j] / n;
    d_mean += delta[j] / n;
  }
  double suu = 0, sud = 0;
  for (size_t j = 0; j < u.size(); ++j) {
    suu += (u[j] - u_mean) * (u[j] - u_mean);
    sud += (u[j] - u_mean) * (delta[j] - d_mean);
  }
  LineFit fit;
  fit.slope = sud / suu;
  double ssr = 0;
  for (size_t j = 0; j < u.size(); ++j) {
    const double r = delta[j] - d_mean - fit.slope * (u[j] - u_mean);
    ssr += r * r;
  }
  fit.slope_se = std::sqrt(ssr / (n - 2) / suu);
  return fit;
}

AxisResiduals AxisStatistics(const std::vector<double>& delta, const std::vector<double>& depth,
                             const std::vector<double>& own) {
  const double n = static_cast<double>(delta.size());
  AxisResiduals axis;
  for (double d : delta) axis.mean += d / n;
  double sum_squares = 0;
  for (double d : delta) sum_squares += (d - axis.mean) * (d - axis.mean);
  axis.std_dev = std::sqrt(sum_squares / (n - 1));
  axis.standard_error = axis.std_dev / std::sqrt(n);
  axis.t = axis.standard_error > 0 ? axis.mean / axis.standard_error : 0;
  const LineFit by_depth = FitLine(depth, delta), by_own = FitLine(own, delta);
  axis.depth_slope = by_depth.slope;
  axis.depth_slope_se = by_depth.slope_se;
  axis.scale_slope = by_own.slope;
  axis.scale_slope_se = by_own.slope_se;
  return axis;
}

bool Varies(const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high - *low > 1e-9 * std::max(1.0, std::abs(*high));
}

// Does one cause, of the size that explains k_z, leave the x and y scale
// slopes observed? χ² of both, each with its own standard error and that of
// k_z carried through the ratio.
bool CauseFits(const BiasSignature& signature, const CameraFrameResiduals& r) {
  if (std::abs(signature.depth_slope) < 1e-6) return false;  // it leaves no depth slope to explain
  const AxisResiduals& z = r.axes[2];
  double chi_square = 0;
  for (int a = 0; a < 2; ++a) {
    const double ratio = (a == 0 ? signature.x_slope : signature.y_slope) / signature.depth_slope;
    const double variance = std::pow(r.axes[a].scale_slope_se, 2) + std::pow(ratio * z.depth_slope_se, 2);
    if (variance <= 0) return false;
    chi_square += std::pow(r.axes[a].scale_slope - ratio * z.depth_slope, 2) / variance;
  }
  return chi_square <= kBiasChiSquare2;
}

std::string Percent(double fraction) {
  std::ostringstream out;
  out << std::setprecision(2) << std::fixed << 100 * fraction << " %";
  return out.str();
}

}  // namespace

StatusOr<CameraFrameResiduals> ComputeCameraFrameResiduals(const Robot& calibrated, const Registration& registration,
                                                           const std::vector<Pose>& camera_from_target,
                                                           const std::vector<LegReadings>& legs,
                                                           const std::vector<int>& left_out) {
  if (legs.size() != camera_from_target.size())
    return Status::BadInput("camera-frame residuals: camera poses and readings differ in number");
  const Pose camera_from_base = Inverse(registration.base_from_camera);
  CameraFrameResiduals result;
  std::array<std::vector<double>, 3> delta, position;
  for (size_t j = 0; j < legs.size(); ++j) {
    if (std::find(left_out.begin(), left_out.end(), static_cast<int>(j)) != left_out.end()) continue;
    const Pose measured = BaseFromPlatform(registration, camera_from_target[j]);  // A'_j
    StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(calibrated, legs[j], measured);
    if (!fk.ok()) {
      ++result.fk_failed;  // a diagnosis, not the calibration: counted, not fatal
      continue;
    }
    const Eigen::Vector3d residual = camera_from_base.rotation * (fk->pose.position - measured.position);
    const Eigen::Vector3d platform_in_camera = camera_from_base * measured.position;
    for (int a = 0; a < 3; ++a) {
      delta[a].push_back(residual[a]);
      position[a].push_back(platform_in_camera[a]);
    }
  }
  result.images = static_cast<int>(delta[2].size());
  if (result.images < 3)
    return Status::Failed("camera-frame residuals: " + std::to_string(result.images) +
                          " images with a converged FK, at least 3 needed");
  for (int a = 0; a < 3; ++a)
    if (!Varies(position[a]))
      return Status::BadInput("camera-frame residuals: the platform does not move along camera axis " +
                              std::string(1, "xyz"[a]));
  result.depth_min = *std::min_element(position[2].begin(), position[2].end());
  result.depth_max = *std::max_element(position[2].begin(), position[2].end());
  for (int a = 0; a < 3; ++a) result.axes[a] = AxisStatistics(delta[a], position[2], position[a]);
  return result;
}

double SignificanceBound(int dof) {
  // t ≈ z + g1/ν + g2/ν² + g3/ν³ + g4/ν⁴ (Abramowitz and Stegun 26.7.5), z = 3.
  const double z = kBiasSignificance, z2 = z * z;
  const double g1 = (z2 + 1) * z / 4;
  const double g2 = ((5 * z2 + 16) * z2 + 3) * z / 96;
  const double g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384;
  const double g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
  const double v = std::max(dof, 1);
  return z + g1 / v + g2 / (v * v) + g3 / (v * v * v) + g4 / (v * v * v * v);
}

namespace {

StatusOr<CameraFrameResiduals> CalibratedResiduals(const Robot& nominal, const CameraCalibrationInput& input,
                                                   const RegistrationOptions& registration_options,
                                                   const CalibrationOptions& calibration_options) {
  StatusOr<CameraCalibrationResult> result =
      CalibrateFromCameraPoses(nominal, input, registration_options, calibration_options);
  if (!result.ok()) return result.status();
  return ComputeCameraFrameResiduals(result->calibration.robot, result->registration, input.camera_from_target,
                                     input.legs);
}

CameraCalibrationInput Without(const CameraCalibrationInput& input, const std::vector<int>& left_out) {
  CameraCalibrationInput kept;
  for (size_t j = 0; j < input.legs.size(); ++j) {
    if (std::find(left_out.begin(), left_out.end(), static_cast<int>(j)) != left_out.end()) continue;
    kept.camera_from_target.push_back(input.camera_from_target[j]);
    kept.legs.push_back(input.legs[j]);
    kept.fk_start.push_back(input.fk_start[j]);
    if (!input.camera_pose_covariance.empty()) kept.camera_pose_covariance.push_back(input.camera_pose_covariance[j]);
  }
  return kept;
}

}  // namespace

BiasCauseModels ScalingBiasModels() {
  const auto scaled = [](bool lateral_too) {
    return [lateral_too](std::vector<Pose> camera_from_target, double error) -> StatusOr<std::vector<Pose>> {
      for (Pose& pose : camera_from_target) {
        pose.position.z() *= 1 + error;
        if (lateral_too) pose.position.head<2>() *= 1 + error;
      }
      return camera_from_target;
    };
  };
  return {scaled(false), scaled(true)};
}

StatusOr<BiasSignatures> SimulateBiasSignatures(const Robot& nominal, const CameraCalibrationInput& input,
                                                const std::vector<int>& left_out,
                                                const RegistrationOptions& registration_options,
                                                CalibrationOptions calibration_options, const BiasCauseModels& models) {
  // Small enough to stay linear, far above the solver's tolerance.
  constexpr double kProbe = 1e-3;
  calibration_options.outliers.enabled = false;
  calibration_options.compute_uncertainty = false;
  const CameraCalibrationInput kept = Without(input, left_out);
  StatusOr<CameraFrameResiduals> base = CalibratedResiduals(nominal, kept, registration_options, calibration_options);
  if (!base.ok()) return base.status();
  BiasSignatures signatures;
  for (bool focal : {true, false}) {
    CameraCalibrationInput probe = kept;
    StatusOr<std::vector<Pose>> moved_poses =
        (focal ? models.focal_length : models.target_scale)(kept.camera_from_target, kProbe);
    if (!moved_poses.ok()) return moved_poses.status();
    probe.camera_from_target = std::move(*moved_poses);
    StatusOr<CameraFrameResiduals> moved =
        CalibratedResiduals(nominal, probe, registration_options, calibration_options);
    if (!moved.ok()) return moved.status();
    BiasSignature& signature = focal ? signatures.focal_length : signatures.target_scale;
    signature.depth_slope = (moved->axes[2].depth_slope - base->axes[2].depth_slope) / kProbe;
    signature.x_slope = (moved->axes[0].scale_slope - base->axes[0].scale_slope) / kProbe;
    signature.y_slope = (moved->axes[1].scale_slope - base->axes[1].scale_slope) / kProbe;
  }
  return signatures;
}

CameraFrameFinding DiagnoseCameraFrameBias(const CameraFrameResiduals& residuals) {
  CameraFrameFinding finding;
  if (residuals.images < kMinImagesForBias) return finding;
  const AxisResiduals& z = residuals.axes[2];
  // The registration absorbs a constant offset along the axis, so a mean
  // alone is rare; a depth slope is what a scale error leaves.
  const bool offset = std::abs(z.t) > SignificanceBound(residuals.images - 1);
  finding.grows_with_depth = std::abs(z.depth_slope) > SignificanceBound(residuals.images - 2) * z.depth_slope_se;
  finding.optical_axis_bias = offset || finding.grows_with_depth;
  if (!finding.optical_axis_bias) return finding;
  finding.text = "a bias along the optical axis";
  if (!finding.grows_with_depth) {
    finding.cause = BiasCause::kOffset;
    finding.text += " (an offset that does not grow with depth)";
    return finding;
  }
  const BiasSignatures signatures = residuals.signatures.value_or(BiasSignatures{});
  const bool focal = CauseFits(signatures.focal_length, residuals);
  const bool scale = CauseFits(signatures.target_scale, residuals);
  if (focal == scale) {
    finding.cause = BiasCause::kUndetermined;
    finding.text += focal ? "; points to the focal length or the target's scale (the lateral slopes cannot tell)"
                          : "; neither the focal length nor the target's scale alone explains it";
    return finding;
  }
  finding.cause = focal ? BiasCause::kFocalLength : BiasCause::kTargetScale;
  const BiasSignature& signature = focal ? signatures.focal_length : signatures.target_scale;
  finding.implied_error = z.depth_slope / signature.depth_slope;
  const std::string size = Percent(std::abs(finding.implied_error));
  if (focal)
    finding.text += "; points to the focal length (camera depths about " + size +
                    (finding.implied_error > 0 ? " too long)" : " too short)");
  else
    finding.text += "; points to the target's scale (target file sizes about " + size +
                    (finding.implied_error > 0 ? " too large)" : " too small)");
  return finding;
}

}  // namespace hexcal

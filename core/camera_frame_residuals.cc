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

// Does one cause, of the size that explains k_z, leave the lateral slope observed?
bool CauseFits(const BiasSignature& signature, double depth_slope, double depth_slope_se, const LateralSlope& lateral) {
  if (std::abs(signature.depth_slope) < 1e-6) return false;  // it leaves no depth slope to explain
  const double ratio = signature.lateral_slope / signature.depth_slope;
  const double se = std::hypot(lateral.se, ratio * depth_slope_se);
  return std::abs(lateral.slope - ratio * depth_slope) <= kBiasSignificance * se;
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
    return Status::Error("camera-frame residuals: camera poses and readings differ in number");
  const Pose camera_from_base = Inverse(registration.base_from_camera);
  CameraFrameResiduals result;
  std::array<std::vector<double>, 3> delta, position;
  for (size_t j = 0; j < legs.size(); ++j) {
    if (std::find(left_out.begin(), left_out.end(), static_cast<int>(j)) != left_out.end()) continue;
    const Pose& measured = camera_from_target[j];
    StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(calibrated, legs[j], BaseFromPlatform(registration, measured));
    if (!fk.ok()) {
      ++result.fk_failed;  // a diagnosis, not the calibration: counted, not fatal
      continue;
    }
    const Pose predicted = Compose(Compose(camera_from_base, fk->pose), registration.platform_from_target);
    for (int a = 0; a < 3; ++a) {
      delta[a].push_back(predicted.position[a] - measured.position[a]);
      position[a].push_back(measured.position[a]);
    }
  }
  result.images = static_cast<int>(delta[2].size());
  if (result.images < 3)
    return Status::Error("camera-frame residuals: " + std::to_string(result.images) +
                         " images with a converged FK, at least 3 needed");
  for (int a = 0; a < 3; ++a)
    if (!Varies(position[a]))
      return Status::Error("camera-frame residuals: the targets do not move along camera axis " +
                           std::string(1, "xyz"[a]));
  result.depth_min = *std::min_element(position[2].begin(), position[2].end());
  result.depth_max = *std::max_element(position[2].begin(), position[2].end());
  for (int a = 0; a < 3; ++a) result.axes[a] = AxisStatistics(delta[a], position[2], position[a]);
  return result;
}

LateralSlope CombinedLateralSlope(const CameraFrameResiduals& residuals) {
  const AxisResiduals &x = residuals.axes[0], &y = residuals.axes[1];
  if (x.scale_slope_se <= 0 || y.scale_slope_se <= 0) return {(x.scale_slope + y.scale_slope) / 2, 0};
  const double wx = 1 / (x.scale_slope_se * x.scale_slope_se), wy = 1 / (y.scale_slope_se * y.scale_slope_se);
  return {(wx * x.scale_slope + wy * y.scale_slope) / (wx + wy), 1 / std::sqrt(wx + wy)};
}

namespace {

// The camera poses with every depth (focal length) or every position (target
// scale) scaled by 1 + error.
std::vector<Pose> Scaled(std::vector<Pose> camera_from_target, bool lateral_too, double error) {
  for (Pose& pose : camera_from_target) {
    pose.position.z() *= 1 + error;
    if (lateral_too) pose.position.head<2>() *= 1 + error;
  }
  return camera_from_target;
}

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

StatusOr<BiasSignatures> SimulateBiasSignatures(const Robot& nominal, const CameraCalibrationInput& input,
                                                const std::vector<int>& left_out,
                                                const RegistrationOptions& registration_options,
                                                CalibrationOptions calibration_options) {
  // Small enough to stay linear, far above the solver's tolerance.
  constexpr double kProbe = 1e-3;
  calibration_options.outliers.enabled = false;
  calibration_options.compute_uncertainty = false;
  CameraCalibrationInput probe = Without(input, left_out);
  StatusOr<CameraFrameResiduals> base = CalibratedResiduals(nominal, probe, registration_options, calibration_options);
  if (!base.ok()) return base.status();
  const LateralSlope base_lateral = CombinedLateralSlope(*base);
  BiasSignatures signatures;
  for (bool lateral_too : {false, true}) {
    probe.camera_from_target = Scaled(Without(input, left_out).camera_from_target, lateral_too, kProbe);
    StatusOr<CameraFrameResiduals> moved =
        CalibratedResiduals(nominal, probe, registration_options, calibration_options);
    if (!moved.ok()) return moved.status();
    BiasSignature& signature = lateral_too ? signatures.target_scale : signatures.focal_length;
    signature.depth_slope = (moved->axes[2].depth_slope - base->axes[2].depth_slope) / kProbe;
    signature.lateral_slope = (CombinedLateralSlope(*moved).slope - base_lateral.slope) / kProbe;
  }
  return signatures;
}

CameraFrameFinding DiagnoseCameraFrameBias(const CameraFrameResiduals& residuals) {
  CameraFrameFinding finding;
  if (residuals.images < kMinImagesForBias) return finding;
  const AxisResiduals& z = residuals.axes[2];
  // The registration absorbs a constant offset along the axis, so a mean
  // alone is rare; a depth slope is what a scale error leaves.
  const bool offset = std::abs(z.t) > kBiasSignificance;
  finding.grows_with_depth = std::abs(z.depth_slope) > kBiasSignificance * z.depth_slope_se;
  finding.optical_axis_bias = offset || finding.grows_with_depth;
  if (!finding.optical_axis_bias) return finding;
  finding.text = "a bias along the optical axis";
  if (!finding.grows_with_depth) {
    finding.cause = BiasCause::kOffset;
    finding.text += " (an offset that does not grow with depth)";
    return finding;
  }
  const BiasSignatures signatures = residuals.signatures.value_or(BiasSignatures{});
  const LateralSlope lateral = CombinedLateralSlope(residuals);
  const bool focal = CauseFits(signatures.focal_length, z.depth_slope, z.depth_slope_se, lateral);
  const bool scale = CauseFits(signatures.target_scale, z.depth_slope, z.depth_slope_se, lateral);
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

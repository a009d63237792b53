#include "session/camera_frame_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "vision/board_pose.h"

namespace hexcal::workflow {
namespace {

// The tags whose four corners `camera` sees inside its image at `camera_from_target` (target unit).
BoardObservation ProjectTarget(const Camera& camera, const Target& target, const Pose& camera_from_target) {
  BoardObservation seen;
  for (int id : target.TagIds()) {
    const std::array<Eigen::Vector3d, 4> corners = target.TagCorners(id);
    std::array<Eigen::Vector2d, 4> pixels;
    bool inside = true;
    for (int k = 0; k < 4 && inside; ++k) {
      const Eigen::Vector3d p = camera_from_target * corners[k];
      if (p.z() > 0) pixels[k] = camera.Project(p);
      inside = p.z() > 0 && pixels[k].x() >= 0 && pixels[k].y() >= 0 && pixels[k].x() <= camera.width &&
               pixels[k].y() <= camera.height;
    }
    if (!inside) continue;
    seen.tag_ids.push_back(id);
    seen.target_points.insert(seen.target_points.end(), corners.begin(), corners.end());
    seen.image_points.insert(seen.image_points.end(), pixels.begin(), pixels.end());
    seen.corner_covariances.push_back(Eigen::Matrix<double, 8, 8>::Zero());  // not refined: 0.1 px each
  }
  return seen;
}

StatusOr<std::vector<Pose>> WithFocalError(const Camera& camera, const Target& target, double robot_per_target_unit,
                                           std::vector<Pose> camera_from_target, double error) {
  Camera longer = camera;
  longer.fx *= 1 + error;
  longer.fy *= 1 + error;
  for (size_t j = 0; j < camera_from_target.size(); ++j) {
    Pose in_target_unit = camera_from_target[j];
    in_target_unit.position /= robot_per_target_unit;
    const BoardPose solved = EstimateBoardPose(longer, ProjectTarget(camera, target, in_target_unit), {});
    if (!solved.has_pose)
      return Status::Failed("pose " + std::to_string(j + 1) + " with a longer focal length: " + solved.message);
    camera_from_target[j] = solved.camera_from_target;
    camera_from_target[j].position *= robot_per_target_unit;
  }
  return camera_from_target;
}

}  // namespace

BiasCauseModels SessionBiasModels(const Camera& camera, const Target& target, double robot_per_target_unit) {
  BiasCauseModels models = ScalingBiasModels();
  models.focal_length = [camera, target, robot_per_target_unit](std::vector<Pose> poses, double error) {
    return WithFocalError(camera, target, robot_per_target_unit, std::move(poses), error);
  };
  return models;
}

std::optional<CameraFrameResiduals> SessionCameraFrameResiduals(const Robot& nominal,
                                                                const CameraCalibrationInput& input,
                                                                const CameraCalibrationResult& result,
                                                                const RegistrationOptions& registration_options,
                                                                const CalibrationOptions& calibration_options,
                                                                const BiasCauseModels& models, const JobHooks& hooks) {
  StatusOr<CameraFrameResiduals> residuals =
      ComputeCameraFrameResiduals(result.calibration.robot, result.registration, input.camera_from_target, input.legs,
                                  result.registration_left_out);
  if (!residuals.ok()) {
    hooks.Note("warning: no bias diagnosis: " + residuals.status().message());
    return std::nullopt;
  }
  // The causes are told apart only for a residual that grows with depth:
  // three more calibrations, not spent on every session.
  if (DiagnoseCameraFrameBias(*residuals).grows_with_depth) {
    StatusOr<BiasSignatures> signatures = SimulateBiasSignatures(nominal, input, result.registration_left_out,
                                                                 registration_options, calibration_options, models);
    if (signatures.ok()) {
      residuals->signatures = *signatures;
    } else {
      hooks.Note("warning: the bias's cause was judged without simulating it: " + signatures.status().message());
    }
  }
  return *residuals;
}

std::string FixedLike(double value, double uncertainty, bool sign) {
  const int decimals =
      uncertainty > 0 ? std::clamp(1 - static_cast<int>(std::floor(std::log10(uncertainty))), 0, 12) : 4;
  std::ostringstream out;
  if (sign) out << std::showpos;
  out << std::fixed << std::setprecision(decimals) << value;
  return out.str();
}

std::string CameraFrameFindingText(const CameraFrameResiduals& residuals) {
  if (residuals.images < kMinImagesForBias)
    return "too few images to diagnose a bias (" + std::to_string(kMinImagesForBias) + " needed)";
  const CameraFrameFinding finding = DiagnoseCameraFrameBias(residuals);
  return finding.optical_axis_bias ? finding.text : "no bias along the optical axis";
}

std::string FormatCameraFrameLine(const CameraFrameResiduals& residuals, const std::string& length_unit) {
  std::ostringstream out;
  out << "camera-frame residuals (" << length_unit << ", " << residuals.images
      << " images, mean ± standard error; robot − camera):";
  for (int a = 0; a < 3; ++a) {
    const AxisResiduals& axis = residuals.axes[a];
    out << (a == 0 ? " " : ", ") << "xyz"[a] << " " << FixedLike(axis.mean, axis.standard_error) << " ± "
        << FixedLike(axis.standard_error, axis.standard_error, false);
  }
  const AxisResiduals& z = residuals.axes[2];
  out << " (t = " << FixedLike(z.t, 1) << ", depth slope " << FixedLike(100 * z.depth_slope, 100 * z.depth_slope_se)
      << " % ± " << FixedLike(100 * z.depth_slope_se, 100 * z.depth_slope_se, false)
      << " %): " << CameraFrameFindingText(residuals);
  return out.str();
}

}  // namespace hexcal::workflow

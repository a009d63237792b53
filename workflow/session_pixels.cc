#include "workflow/session_pixels.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "vision/board_pose.h"
#include "vision/measure.h"
#include "workflow/screened_joint_fit.h"

namespace hexcal::workflow {
namespace {

// The corners of every image: those detected earlier in this run, the others
// detected again. An image whose board no longer fits is nullopt (it had a
// usable pose, so this only happens when the image changed under a writer
// that ignores the lock).
StatusOr<std::vector<std::optional<BoardObservation>>> ObserveImages(
    const std::vector<std::string>& files, const std::map<std::string, BoardObservation>& known,
    const Camera& camera, const Target& target, const JobHooks& hooks) {
  std::vector<std::string> to_detect;
  for (const std::string& file : files)
    if (known.count(file) == 0) to_detect.push_back(file);
  MeasureOptions options;
  options.keep_observations = true;
  std::map<std::string, BoardObservation> detected;
  if (!to_detect.empty()) {
    StatusOr<std::vector<ImageMeasurement>> measured = MeasureImages(to_detect, camera, target, options, hooks);
    if (!measured.ok()) return measured.status();
    for (ImageMeasurement& m : *measured)
      if (m.pose.status == PoseStatus::kOk && m.observation) detected[m.file] = std::move(*m.observation);
  }
  std::vector<std::optional<BoardObservation>> observations;
  for (const std::string& file : files) {
    const auto k = known.find(file);
    const auto d = detected.find(file);
    observations.push_back(k != known.end()   ? std::optional<BoardObservation>(k->second)
                           : d != detected.end() ? std::optional<BoardObservation>(d->second)
                                                 : std::nullopt);
  }
  return observations;
}

// camera_from_target in the robot unit from the corners, with the fitted
// camera and the target's points scaled by the fitted scale.
std::optional<Pose> BoardPoseWith(const Camera& camera, double target_scale, double target_to_robot,
                                  BoardObservation observation) {
  for (Eigen::Vector3d& p : observation.target_points) p *= target_scale;
  const BoardPose board = EstimateBoardPose(camera, observation, BoardPoseOptions{});
  if (!board.has_pose) return std::nullopt;
  Pose pose = board.camera_from_target;
  pose.position *= target_to_robot;
  return pose;
}

PixelCalibrationInput FitInput(const SessionPixelSetup& setup, const CameraCalibrationResult& two_stage,
                               const std::vector<std::optional<BoardObservation>>& seen) {
  PixelCalibrationInput input{setup.nominal,
                              two_stage.calibration.robot,
                              setup.camera,
                              setup.target_to_robot,
                              two_stage.registration.base_from_camera,
                              two_stage.registration.platform_from_target,
                              {}};
  for (size_t j = 0; j < seen.size(); ++j) {
    PixelImage image;
    image.observation = *seen[j];
    image.legs = setup.calibration_legs[j];
    image.base_from_platform = setup.nominal.PoseFromVector(two_stage.measurements[j].pose);
    input.images.push_back(image);
  }
  return input;
}

}  // namespace

const OptionSpec<FromPixelsRequest>& PixelEstimatesOption() {
  static const OptionSpec<FromPixelsRequest> spec = [] {
    OptionSpec<FromPixelsRequest> s;
    s.key = "estimate";
    s.label = "Estimate";
    s.type = OptionType::kChoiceList;
    s.choices = {"focal", "principal", "scale", "none"};
    s.help = "camera and target quantities the calibration from pixels estimates, comma-separated: focal, "
             "principal, scale; or none";
    s.get_choice = [](const FromPixelsRequest& r) {
      std::string text;
      if (r.focal) text += ",focal";
      if (r.principal_point) text += ",principal";
      if (r.target_scale) text += ",scale";
      return text.empty() ? std::string("none") : text.substr(1);
    };
    s.set_choice = [](FromPixelsRequest& r, const std::string& list) {
      r.focal = r.principal_point = r.target_scale = false;
      for (const std::string& word : SplitOptionList(list)) {
        r.focal = r.focal || word == "focal";
        r.principal_point = r.principal_point || word == "principal";
        r.target_scale = r.target_scale || word == "scale";
      }
    };
    return s;
  }();
  return spec;
}

StatusOr<FromPixelsRequest> ParsePixelEstimates(const std::string& list) {
  FromPixelsRequest request;
  const OptionSpec<FromPixelsRequest>& spec = PixelEstimatesOption();
  if (Status s = ApplyOptionText(spec, list, &request, spec.Flag()); !s.ok()) return s;
  // "none" is the whole list or absent: with a quantity beside it, it would mean both.
  const std::vector<std::string> words = SplitOptionList(list);
  if (words.size() > 1 && std::find(words.begin(), words.end(), "none") != words.end())
    return Status::BadInput(spec.Flag() + ": none stands alone (no quantity estimated), not in a list");
  request.enabled = true;
  return request;
}

StatusOr<SessionPixelFit> FitSessionFromPixels(const SessionPixelSetup& setup,
                                               const CameraCalibrationResult& two_stage,
                                               const FromPixelsRequest& request, const OutlierScreening& screening,
                                               const JobHooks& hooks) {
  hooks.Stage("corners (calibration from pixels)");
  StatusOr<std::vector<std::optional<BoardObservation>>> seen =
      ObserveImages(setup.calibration_images, setup.known_observations, setup.camera, setup.target, hooks);
  if (!seen.ok()) return seen.status();
  StatusOr<std::vector<std::optional<BoardObservation>>> held_out =
      ObserveImages(setup.held_out_images, setup.known_observations, setup.camera, setup.target, hooks);
  if (!held_out.ok()) return held_out.status();
  for (size_t j = 0; j < seen->size(); ++j) {
    if (!(*seen)[j]) {
      return Status::Failed(setup.calibration_images[j] +
                            ": its corners no longer give a board pose (the image changed while calibrating?); run "
                            "again");
    }
  }
  PixelCalibrationOptions options;
  options.estimate_focal = request.focal;
  options.estimate_principal_point = request.principal_point;
  options.estimate_target_scale = request.target_scale;
  options.leg_sigma = setup.noise.LegStdDev();
  hooks.Stage("calibrate from pixels");
  StatusOr<PixelCalibrationResult> fit = ScreenedJointFit(FitInput(setup, two_stage, *seen), options, screening,
                                                          &CalibrateFromPixels, &PixelCalibrationInput::images, hooks);
  if (!fit.ok()) return fit.status();
  SessionPixelFit result{std::move(*fit), {}, {}};
  auto pose_of = [&](const std::optional<BoardObservation>& observation) {
    return observation ? BoardPoseWith(result.fit.camera, result.fit.target_scale, setup.target_to_robot, *observation)
                       : std::nullopt;
  };
  for (const std::optional<BoardObservation>& o : *seen) result.calibration_poses.push_back(pose_of(o));
  for (const std::optional<BoardObservation>& o : *held_out) result.held_out_poses.push_back(pose_of(o));
  return result;
}

PixelFitSummary SummarizeSessionPixelFit(const SessionPixelFit& session, const TwoStageComparison& two_stage) {
  const PixelCalibrationResult& fit = session.fit;
  PixelFitSummary summary;
  summary.images = static_cast<int>(fit.base_from_platform.size());
  summary.corners = fit.corners;
  summary.leg_rows = fit.leg_rows;
  summary.reprojection_rms_px = fit.reprojection_rms_px;
  summary.leg_residual_rms = fit.leg_residual_rms;
  summary.variance_factor = fit.variance_factor;
  summary.iterations = fit.iterations;
  for (const PixelExtraEstimate& e : fit.extras) summary.estimated.push_back({e.name, e.file_value, e.estimate, e.sigma});
  for (const PixelCorrelation& c : fit.strong_correlations)
    summary.strong_correlations.push_back({c.first, c.second, c.correlation});
  summary.two_stage = two_stage;
  summary.mean_parameter_sigma = fit.calibration.StdDevs().mean();
  return summary;
}

}  // namespace hexcal::workflow

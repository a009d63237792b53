// The bias diagnosis of a session calibration in the camera frame, as
// `calibrate --session` computes it and its summary prints it
// (docs/calibration.md, "Bias along the optical axis"; the figures and the
// rule are core/camera_frame_residuals.h). A diagnosis, not a step of the
// calibration: when it cannot be computed the report simply has none.
//
//   report.camera_frame_residuals = SessionCameraFrameResiduals(
//       nominal, input, result, registration, calibration, SessionBiasModels(camera, target, 0.1));
//   if (report.camera_frame_residuals) out << FormatCameraFrameLine(*report.camera_frame_residuals, "cm") << "\n";
#pragma once

#include <optional>
#include <string>

#include "core/camera_frame_residuals.h"
#include "core/job_hooks.h"
#include "core/registration.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::workflow {

// The two causes with the session's camera and target: a focal length error
// as the board poses solved again (vision/board_pose.h) from the target's
// corners, projected with `camera` at each pose, with fx and fy (1 + error)
// times larger — the lens's distortion then adds lateral and rotation errors
// a plain depth scale misses (a real 0.5 % error of the demo's camera, 100
// images: x and y slopes of −0.07 %, fitting neither plain model); a target
// scale error as every position scaled (exact). `robot_per_target_unit`
// converts the target's length unit to the robot's.
BiasCauseModels SessionBiasModels(const Camera& camera, const Target& target, double robot_per_target_unit);

// The residuals over the calibration images `input` (robot unit) with the
// calibrated robot and frames of `result`, leaving out the images of
// result.registration_left_out; when they grow with depth, the signatures of
// the two causes of `models` simulated on the same images with the same
// options. None, with a warning through hooks.Note, when they cannot be
// computed (fewer than 3 images, a pose set without spread).
std::optional<CameraFrameResiduals> SessionCameraFrameResiduals(
    const Robot& nominal, const CameraCalibrationInput& input, const CameraCalibrationResult& result,
    const RegistrationOptions& registration_options, const CalibrationOptions& calibration_options,
    const BiasCauseModels& models, const JobHooks& hooks = {});

// One line, e.g. "camera-frame residuals (cm, 24 images, mean ± standard
// error): x +0.00003 ± 0.00061, y …, z … (t = -0.1, depth slope -0.38 % ±
// 0.04 %): a bias along the optical axis; points to the focal length (…)".
std::string FormatCameraFrameLine(const CameraFrameResiduals& residuals, const std::string& length_unit);

// The finding alone: DiagnoseCameraFrameBias's text, or what was not found.
std::string CameraFrameFindingText(const CameraFrameResiduals& residuals);

// `value` with the decimals that show `uncertainty` to 2 significant digits.
std::string FixedLike(double value, double uncertainty, bool sign = true);

}  // namespace hexcal::workflow

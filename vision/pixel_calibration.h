// Calibration from pixels: the 42 kinematic parameters fitted to the tag
// corners themselves, not to board poses computed from them first
// (docs/calibration.md, "Calibration from pixels").
//
// One least-squares problem (Ceres, Levenberg–Marquardt) over
//   - the 42 parameters (a_i, b_i, l_i);
//   - the platform pose A_j of every image (base_from_platform), tied to the
//     image's leg readings;
//   - optionally a common scale φ of the focal lengths (fx, fy = φ fx0, φ fy0),
//     the principal point (cx, cy) and the target's scale s;
// with two kinds of residual:
//   - each tag's 4 corners: the reprojection error of X⁻¹ · A_j · Y · (s P)
//     through the camera model (distortion as in the camera file), whitened
//     by the corners' 8×8 covariance from the edge fit (0.1 px independent
//     where the corners were not refined);
//   - each leg reading: (|A_j b_i − a_i| − (l_i + L_ij)) / σ_L, σ_L the
//     reading noise's standard deviation.
// X = base_from_camera and Y = platform_from_target stay fixed where the
// two-stage registration put them: they fix the gauge (the 12 rigid
// freedoms of base and platform frames, docs/session.md, "The gauge"), so the
// results are in the same frames as the two-stage calibration's.
//
// Uncertainty: the covariance of the 42 parameters and of the camera and
// target quantities is the inverse of JᵀJ with the pose blocks eliminated
// (Schur complement), scaled by max(1, s²), s² = Σ r² / (m − n) the variance
// factor (as calibrate's kAtLeastAPriori): the a priori covariance, larger
// when the data scatter more than the corner and reading noise say.
//
//   PixelCalibrationInput input{nominal, start, camera, target_to_robot, X, Y, images};
//   StatusOr<PixelCalibrationResult> fit = CalibrateFromPixels(input, PixelCalibrationOptions{});
#pragma once

#include "core/job_hooks.h"
#include "core/status.h"
#include "vision/pixel_calibration_types.h"

namespace hexcal {

// Fails with the reason for invalid options, fewer than 7 images, an image
// without corners, non-finite input, or a solve that does not converge;
// Status::Cancelled when hooks.cancel is raised.
StatusOr<PixelCalibrationResult> CalibrateFromPixels(const PixelCalibrationInput& input,
                                                     const PixelCalibrationOptions& options,
                                                     const JobHooks& hooks = {});

}  // namespace hexcal

// Calibration from points: the 42 kinematic parameters fitted to the points a
// laser tracker measured, not to the poses fitted to them first (issue 38;
// docs/calibration.md, "Calibration from points"). The analogue for a points
// session of the calibration from pixels (vision/pixel_calibration.h).
//
// One least-squares problem (Ceres, Levenberg–Marquardt, the poses eliminated
// by the dense Schur complement) over
//   - the 42 parameters (a_i, b_i, l_i);
//   - the platform pose A_j (base_from_platform) of every pose;
//   - the reflectors' positions r_k in the platform frame (optional, on by
//     default);
// with two kinds of residual:
//   - each measured point: (X⁻¹ · A_j · r_k − m_jk) / σ_jk, 3 per point,
//     σ_jk the point's σ per coordinate (point_calibration_cost.h);
//   - each leg reading: (|A_j b_i − a_i| − (l_i + L_ij)) / σ_L
//     (leg_reading_residual.h), σ_L the reading noise's standard deviation.
//
// The gauge. Base and platform frames have 12 rigid freedoms that no residual
// sees. X = base_from_tracker stays where the registration put it: that fixes
// the base frame (moving X moves every a_i and A_j with it; estimating X
// jointly would be the same freedom again). The platform frame is fixed by the
// reflectors: held at their start values, or, when estimated, moved only
// within the subspace that keeps their centroid and mean orientation at the
// start's (point_calibration_cost.h). So the results are in the frames of the
// two-stage calibration the fit starts from, and 42 + 3K − 6 global unknowns
// remain (42 with the reflectors held).
//
// Uncertainty: the covariance of the global unknowns is the inverse of JᵀJ
// with the pose blocks eliminated (Schur complement), scaled by max(1, s²),
// s² = Σ r² / (m − n) the variance factor, as the calibration from pixels.
// Identifiability: that reduced information matrix scaled to unit diagonal;
// its rank and smallest/largest eigenvalue ratio are reported, and a ratio
// below 1e-12 is refused naming the unknowns of the weakest direction.
//
//   PointCalibrationInput input{nominal, start, X, reflectors_in_platform, poses};
//   StatusOr<PointCalibrationResult> fit = CalibrateFromPoints(input, PointCalibrationOptions{});
#pragma once

#include "core/job_hooks.h"
#include "core/point_calibration_types.h"
#include "core/status.h"

namespace hexcal {

// Bad input, named: invalid options, fewer than 7 poses, fewer than 3
// reflectors or reflectors on one line, a reflector named twice, a pose with
// fewer than 3 points, its points on one line, a point not among the
// reflectors or measured twice, a σ not positive, a non-finite value.
// Failed: the data do not determine the unknowns (named: the weakest
// direction), or the solve does not converge. Cancelled: hooks.cancel raised.
StatusOr<PointCalibrationResult> CalibrateFromPoints(const PointCalibrationInput& input,
                                                     const PointCalibrationOptions& options,
                                                     const JobHooks& hooks = {});

}  // namespace hexcal

// Implicit calibration of the 42 kinematic parameters (paper section 5.2).
//
// For each leg i, Levenberg-Marquardt (Ceres) from the nominal parameters
// P_i = (a_i, b_i, l_i) minimises
//   Σ_j ρ(r_ij²),  r_ij = F_ij / w_ij,
//   F_ij = |P_j + R_j b_i - a_i|² - (L_ij + l_i)²                  (eq. 4)
// with the analytic row [-2v, 2R_jᵀv, -2(L_ij + l_i)] (eq. 5 with its factor 2).
// w_ij = 1 (the paper), or with `weighted` the standard deviation of F_ij under
// the noise model (noise_model.h), evaluated once with the nominal parameters.
// ρ is the identity or a Huber / Cauchy loss. The six legs share the poses but
// no parameters, so they are six independent problems, solved in parallel.
//
// Uncertainty of leg i: C_i = s_i² (J_iᵀ J_i)⁻¹ at the solution (ceres::Covariance,
// J_i the Jacobian of the r_ij), scaled by the residual variance
// s_i² = Σ_j r_ij² / (N - 7). Unweighted, s_i² estimates Var(F) from the fit.
// Weighted, the r_ij have unit variance if the noise model is right, so s_i² is
// the variance factor: ≈ 1 when the model matches the data, and the scaling
// makes σ follow the observed scatter rather than the assumed noise.
// Outliers (options.outliers, outlier_screening.h): a robust refit names the
// rows whose residual is far beyond the noise model and, by default, leaves
// them out of their leg's final least-squares fit.
// Identifiability: the singular values of J_i, the directions with
// σ_k / σ_max < weak_direction_ratio, and the parameter pairs of a leg whose
// correlation |ρ| exceeds correlation_threshold.
//
// A request that cannot give meaningful numbers fails with the reason: fewer
// than 7 measurements, non-finite input, leg readings more than a stroke length
// outside the stroke (a file in another length unit), a leg whose Jacobian is rank-deficient
// (repeated or too alike poses), a solve that does not converge. A cancelled
// calibration returns Status::Cancelled and no parameters.
//
//   CalibrationOptions options;              // unweighted, no robust loss
//   StatusOr<CalibrationResult> result = Calibrate(nominal, measurements, options);
//   if (!result.ok()) return result.status();
//   SaveRobot(result->robot, "calibrated.yaml");  // or SaveCalibratedRobot (calibration_file.h)
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/calibration_types.h"
#include "core/identification.h"
#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/status.h"

namespace hexcal {

struct CalibrationResult {
  Robot robot;  // the nominal robot with the calibrated parameters
  std::array<LegCalibration, kNumLegs> legs;
  int num_measurements = 0;

  ParameterVector Estimates() const;  // [a_1, b_1, l_1, ...] as ParametersOf
  ParameterVector StdDevs() const;
};

// "ax", "ay", "az", "bx", "by", "bz", "l" for k = 0..6.
const char* ParameterName(int k);

// The checks of the request that Calibrate makes first: valid options, finite
// parameters and measurements, at least 7 measurements, readings near the stroke. A failure here is bad
// input; a failure of Calibrate past it is a pose set or solve that does not work.
Status CheckCalibrationInput(const Robot& nominal, const std::vector<Measurement>& measurements,
                             const CalibrationOptions& options);

// hooks.Progress(legs_done, kNumLegs) as legs finish; hooks.cancel, when
// raised, stops the solves at their next iteration (Status::Cancelled).
StatusOr<CalibrationResult> Calibrate(const Robot& nominal, const std::vector<Measurement>& measurements,
                                      const CalibrationOptions& options = {}, const JobHooks& hooks = {});

}  // namespace hexcal

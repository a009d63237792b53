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
#include <optional>
#include <string>
#include <vector>

#include "core/identification.h"
#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/noise_model.h"
#include "core/option_spec.h"
#include "core/outlier_screening.h"
#include "core/status.h"

namespace hexcal {

enum class RobustLoss { kNone, kHuber, kCauchy };
// How σ follows the fit: kAPosteriori scales (JᵀJ)⁻¹ by the variance factor
// s²; kAtLeastAPriori (weighted only) by max(1, s²), for noise models that are
// known, e.g. per-pose camera covariances (registration.h).
enum class UncertaintyScale { kAPosteriori, kAtLeastAPriori };
std::optional<RobustLoss> ParseRobustLoss(const std::string& text);  // "none" | "huber" | "cauchy"
const char* RobustLossName(RobustLoss loss);

struct CalibrationOptions {
  RobustLoss loss = RobustLoss::kNone;
  // Residual size where the robust loss starts to down-weight: unweighted, a
  // leg-length error in the robot unit (F ≈ 2ℓδ, converted with each leg's mean
  // length ℓ); weighted, a number of standard deviations. Must be > 0.
  double loss_scale = 1.0;
  bool weighted = false;  // divide each F_ij by its standard deviation under `noise`
  NoiseModel noise;       // used when weighted

  int max_iterations = 100;            // LM iterations per leg; hitting it is a failure
  double function_tolerance = 1e-12;   // stop when the relative cost decrease is below this
  double parameter_tolerance = 1e-12;  // stop when |step| <= tol (|P_i| + tol) (robot unit)
  // A leg whose Jacobian at the start has σ_min / σ_max below this cannot be
  // identified from the poses: an error. Unit-free (every column of J is a
  // length). Along such a direction the noise is amplified about 1/ratio times,
  // so below 1e-6 the error is the size of the robot for any real sensor; noisy
  // copies of one pose give ~1e-9, one orientation ~1e-7, random poses ~1e-3.
  double rank_tolerance = 1e-6;
  // Report directions with σ_k / σ_max below this as unidentifiable. Unit-free.
  double weak_direction_ratio = 1e-4;
  double correlation_threshold = 0.95;  // report pairs with |correlation| above this
  bool compute_uncertainty = true;      // covariance and identifiability report
  UncertaintyScale uncertainty_scale = UncertaintyScale::kAPosteriori;
  int num_threads = 0;                  // legs solved at once; 0 = every core
  OutlierScreening outliers;            // off by default; needs weighted and loss none

  // The ranges of CalibrationOptionSpecs(), then the rules between options.
  bool IsValid(std::string* error) const;
};

// The descriptors of the options `hexcal calibrate --measurements` takes
// (loss, loss_scale, weighted): IsValid checks their ranges, and the CLI
// flags and the table in docs/cli.md are made from them.
const OptionTable<CalibrationOptions>& CalibrationOptionSpecs();

// A direction in a leg's parameter space (a_x a_y a_z b_x b_y b_z l) that the
// poses barely constrain: a unit vector and its singular value ratio.
struct WeakDirection {
  double ratio = 0;  // σ_k / σ_max
  LegParameters direction = LegParameters::Zero();
};

struct CorrelatedPair {
  int first = 0, second = 0;  // parameter indices within the leg, 0..6 (ParameterName)
  double correlation = 0;
};

struct LegCalibration {
  LegParameters initial = LegParameters::Zero();   // the nominal parameters
  LegParameters estimate = LegParameters::Zero();  // robot unit
  // Covariance s² (JᵀJ)⁻¹ (robot unit²) and σ = √diag; only when has_uncertainty,
  // which needs compute_uncertainty and more than 7 measurements (7 fit exactly).
  bool has_uncertainty = false;
  InfoBlock covariance = InfoBlock::Zero();
  LegParameters std_dev = LegParameters::Zero();
  double variance_factor = 0;  // s² = Σ r² / (N - 7): F units² unweighted, unit-free weighted
  double residual_rms = 0;     // RMS over the rows fitted of |v| - (L + l) at the estimate, robot unit
  int rows_used = 0;           // measurements in the fit: all but the excluded outliers
  double initial_cost = 0;     // Ceres cost ½ Σ ρ(r²) at the start and at the end
  double final_cost = 0;
  int iterations = 0;
  std::string termination;  // Ceres termination type, e.g. "CONVERGENCE"
  std::string solver_message;
  // Identifiability (compute_uncertainty): singular values of J, descending.
  LegParameters singular_values = LegParameters::Zero();
  std::vector<WeakDirection> unidentifiable;
  std::vector<CorrelatedPair> correlated;
  // With options.outliers.enabled: the rows that failed the screening, by measurement.
  std::vector<RowOutlier> outliers;
};

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

// The options of the per-leg calibration and what it finds for one leg
// (calibration.h has the model, the maths and the usage), apart from it so
// that the leg's least-squares problem (calibration_leg.h), which Calibrate
// runs, can use them without including the function that runs it.
//
//   CalibrationOptions options;       // unweighted, no robust loss
//   options.weighted = true;          // r = F / σ_F under options.noise
//   options.outliers.enabled = true;  // outlier_screening.h
//   std::string error;
//   if (!options.IsValid(&error)) return Status::BadInput("calibration options: " + error);
//   const LegCalibration& leg = Calibrate(nominal, measurements, options)->legs[2];  // σ: leg.std_dev
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/identification.h"
#include "core/noise_model.h"
#include "core/option_spec.h"
#include "core/outlier_screening.h"

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
  int num_threads = 0;        // legs solved at once; 0 = every core
  OutlierScreening outliers;  // off by default; needs weighted and loss none

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

}  // namespace hexcal

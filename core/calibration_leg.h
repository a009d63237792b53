// The least-squares problem of one leg, for core/calibration.cc, and its fit
// with the outlier screening of outlier_screening.h. Internal: Calibrate
// (calibration.h) is the API.
//
// Leg i's problem is Σ_j ρ(r_j²), r_j = F_ij / w_j (calibration.h), over the
// rows j of `LegData`; `Without` drops rows (screened outliers).
#pragma once

#include <string>
#include <vector>

#include "core/calibration_types.h"
#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/status.h"

namespace hexcal {

// One leg's least-squares problem: the measured poses, that leg's readings
// and the weight w_j of each residual (1 unweighted).
struct LegData {
  std::vector<Pose> poses;
  std::vector<double> readings;
  std::vector<double> weights;

  size_t size() const { return poses.size(); }
  // The same problem without the rows `excluded` (ascending indices).
  LegData Without(const std::vector<int>& excluded) const;
};

std::string LegLabel(int leg);  // "leg 3" for leg index 2

StatusOr<LegData> MakeLegData(const Robot& nominal, int leg, const std::vector<Measurement>& measurements,
                              const std::vector<Pose>& poses, const CalibrationOptions& options);

// An error when the leg's Jacobian at `parameters` has σ_min/σ_max below
// options.rank_tolerance; `context` ends the message's first clause.
Status CheckRank(int leg, const LegData& data, const LegParameters& parameters, const CalibrationOptions& options,
                 const std::string& context = "");

// Levenberg–Marquardt from `start` with options.loss; the uncertainty and
// identifiability report when options.compute_uncertainty. A solve that ends
// without CONVERGENCE is an error (NotConverged) when `must_converge`, else
// its last parameters are returned without uncertainty (a screening start).
StatusOr<LegCalibration> CalibrateLeg(int leg, const LegData& data, const LegParameters& start,
                                      const CalibrationOptions& options, const JobHooks& hooks,
                                      bool must_converge = true);
bool Converged(const LegCalibration& result);
Status NotConverged(int leg, const LegCalibration& result);  // "leg 3: the calibration did not converge (...)"

// CalibrateLeg with the screening of outlier_screening.h (options.outliers):
// the final fit without the flagged rows, or with them when options.outliers.keep.
StatusOr<LegCalibration> CalibrateLegScreened(int leg, const LegData& data, const LegParameters& nominal,
                                              const CalibrationOptions& options, const JobHooks& hooks);

}  // namespace hexcal

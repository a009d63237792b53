#include "core/outlier_screening.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/calibration_cost.h"
#include "core/calibration_leg.h"
#include "core/csv.h"

namespace hexcal {
namespace {

// Below 3 σ the screening flags about 0.3 % of good rows (one every other
// 24-image session); above 100 σ it is off in all but name.
constexpr double kMinThreshold = 3, kMaxThreshold = 100;

}  // namespace

bool OutlierScreening::IsValid(std::string* error) const {
  if (threshold >= kMinThreshold && threshold <= kMaxThreshold) return true;
  *error = "outlier threshold must be between " + FormatNumber(kMinThreshold) + " and " + FormatNumber(kMaxThreshold) +
           " standard deviations, got " + FormatNumber(threshold);
  return false;
}

const OptionTable<OutlierScreening>& OutlierScreeningOptions() {
  static const OptionTable<OutlierScreening> table = [] {
    OptionSpec<OutlierScreening> threshold;
    threshold.key = "outlier_threshold";
    threshold.label = "Outlier threshold";
    threshold.unit = "sigma";
    threshold.min = kMinThreshold;
    threshold.max = kMaxThreshold;
    threshold.help =
        "a leg reading whose residual exceeds this many standard deviations of the noise model is an "
        "outlier (docs/calibration.md)";
    threshold.get_number = [](const OutlierScreening& o) { return o.threshold; };
    threshold.set_number = [](OutlierScreening& o, double v) { o.threshold = v; };
    OptionSpec<OutlierScreening> keep;
    keep.key = "keep_outliers";
    keep.label = "Keep outliers in the fit";
    keep.type = OptionType::kFlag;
    keep.help = "keep the outliers in their leg's fit; they are still named";
    keep.get_number = [](const OutlierScreening& o) { return o.keep ? 1.0 : 0.0; };
    keep.set_number = [](OutlierScreening& o, double v) { o.keep = v != 0; };
    return OptionTable<OutlierScreening>{threshold, keep};
  }();
  return table;
}

double RobustScatter(const std::vector<double>& z, int parameters) {
  const int n = static_cast<int>(z.size());
  if (n == 0) return 0;
  std::vector<double> magnitudes;
  for (double value : z) magnitudes.push_back(std::abs(value));
  std::nth_element(magnitudes.begin(), magnitudes.begin() + n / 2, magnitudes.end());
  double median = magnitudes[n / 2];
  if (n % 2 == 0) median = (median + *std::max_element(magnitudes.begin(), magnitudes.begin() + n / 2)) / 2;
  // 1.4826 = 1/Φ⁻¹(3/4): the median |z| of a unit Gaussian is 0.6745.
  const double dof_correction = n > parameters ? std::sqrt(static_cast<double>(n) / (n - parameters)) : 1.0;
  return 1.4826 * median * dof_correction;
}

std::vector<int> FlagOutliers(const std::vector<double>& z, int parameters, double threshold) {
  const double bar = threshold * std::max(1.0, RobustScatter(z, parameters));
  std::vector<int> flagged;
  for (size_t j = 0; j < z.size(); ++j)
    if (std::abs(z[j]) > bar) flagged.push_back(static_cast<int>(j));
  return flagged;
}

namespace {

// z_j = −r_j and (L + l) − |v| of every row at `parameters` (outlier_screening.h).
void RowResiduals(const LegData& data, const LegParameters& parameters, std::vector<double>* z,
                  std::vector<double>* lengths) {
  const Leg leg = LegFromParameters(parameters.data());
  for (size_t j = 0; j < data.size(); ++j) {
    z->push_back(-ImplicitResidual(leg, data.poses[j], data.readings[j]) / data.weights[j]);
    lengths->push_back(data.readings[j] + leg.offset - LegVector(leg, data.poses[j]).norm());
  }
}

std::vector<double> ZOf(const LegData& data, const LegParameters& parameters) {
  std::vector<double> z, lengths;
  RowResiduals(data, parameters, &z, &lengths);
  return z;
}

// The Cauchy fit of the screening at scale 3 σ, from two starts: the nominal
// parameters and the least-squares estimate. A far-off row can bend the
// least-squares fit into another basin of the robust cost (seen on INRIA
// with poses of a small box: 1 cm moved every other row by 60 σ), and a
// nominal robot far from the truth could start in a wrong one too: the lower
// robust cost wins. When the scatter ŝ there exceeds the model's, once more
// at 3 ŝ so that the screening fit keeps its efficiency. The fits need not
// converge: they only lead to the estimate z is read at.
StatusOr<LegParameters> RobustEstimate(int leg, const LegData& data, const LegParameters& nominal,
                                       const LegParameters& least_squares, const CalibrationOptions& options,
                                       const JobHooks& hooks) {
  CalibrationOptions robust = options;
  robust.loss = RobustLoss::kCauchy;
  robust.loss_scale = kScreeningCauchyScale;
  robust.compute_uncertainty = false;
  std::optional<LegCalibration> best;
  for (const LegParameters& start : {nominal, least_squares}) {
    StatusOr<LegCalibration> fit = CalibrateLeg(leg, data, start, robust, hooks, /*must_converge=*/false);
    if (!fit.ok()) return fit.status();
    if (!best || fit->final_cost < best->final_cost) best = std::move(*fit);
  }
  const double scatter = RobustScatter(ZOf(data, best->estimate), kParamsPerLeg);
  if (scatter <= 1) return best->estimate;
  robust.loss_scale = kScreeningCauchyScale * scatter;
  StatusOr<LegCalibration> settled = CalibrateLeg(leg, data, best->estimate, robust, hooks, /*must_converge=*/false);
  if (!settled.ok()) return settled.status();
  return settled->estimate;
}

}  // namespace

StatusOr<LegCalibration> CalibrateLegScreened(int leg, const LegData& data, const LegParameters& nominal,
                                              const CalibrationOptions& options, const JobHooks& hooks) {
  // Only a start when rows are flagged and excluded: it need not converge then.
  StatusOr<LegCalibration> fit = CalibrateLeg(leg, data, nominal, options, hooks, /*must_converge=*/false);
  if (!fit.ok()) return fit;
  if (static_cast<int>(data.size()) < kMinRowsToScreen) return Converged(*fit) ? fit : NotConverged(leg, *fit);
  StatusOr<LegParameters> robust = RobustEstimate(leg, data, nominal, fit->estimate, options, hooks);
  if (!robust.ok()) return robust.status();
  std::vector<double> z, lengths;
  RowResiduals(data, *robust, &z, &lengths);
  const std::vector<int> flagged = FlagOutliers(z, kParamsPerLeg, options.outliers.threshold);
  const bool exclude = !options.outliers.keep;
  if ((flagged.empty() || !exclude) && !Converged(*fit)) {
    std::string kept;
    for (int j : flagged)
      kept += (kept.empty() ? "" : ", ") + std::to_string(j + 1) + " (z = " + FormatNumber(z[j]) + ")";
    const Status failed = NotConverged(leg, *fit);
    return kept.empty() ? failed : Status::Failed(failed.message() + "; outliers kept in its fit: measurement " + kept);
  }
  if (flagged.empty()) return fit;

  std::vector<RowOutlier> outliers;
  for (int j : flagged) outliers.push_back({j, lengths[j], z[j], exclude});
  if (exclude) {
    const LegData kept = data.Without(flagged);
    const std::string context = " left after excluding " + std::to_string(flagged.size()) + " outlier(s)";
    if (kept.size() < static_cast<size_t>(kParamsPerLeg)) {
      return Status::Failed(LegLabel(leg) + ": " + std::to_string(kept.size()) + " measurements" + context +
                            ", fewer than its 7 parameters; check the readings or keep the outliers");
    }
    if (Status s = CheckRank(leg, kept, nominal, options, context); !s.ok()) return s;
    fit = CalibrateLeg(leg, kept, nominal, options, hooks);
    if (!fit.ok()) return fit;
  }
  fit->outliers = std::move(outliers);
  return fit;
}

std::array<std::vector<RowOutlier>, kNumLegs> ScreenJointFitReadings(const std::vector<LegReadings>& leg_z,
                                                                     const OutlierScreening& screening, double sigma) {
  std::array<std::vector<RowOutlier>, kNumLegs> outliers;
  for (int i = 0; i < kNumLegs; ++i) {
    std::vector<double> z;
    for (const LegReadings& row : leg_z) z.push_back(row[i]);
    if (static_cast<int>(z.size()) < kMinRowsToScreen) continue;
    const double bar = screening.threshold * std::max(1.0, RobustScatter(z, kParamsPerLeg));
    for (size_t j = 0; j < z.size(); ++j) {
      if (std::abs(z[j]) > bar) outliers[i].push_back({static_cast<int>(j), z[j] * sigma, z[j], !screening.keep});
    }
  }
  return outliers;
}

}  // namespace hexcal

#include "core/outlier_screening.h"

#include <algorithm>
#include <cmath>

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

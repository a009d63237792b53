#include "core/error_stats.h"

#include <algorithm>
#include <cmath>

namespace hexcal {

ErrorStats SummarizeErrors(const std::vector<double>& values) {
  ErrorStats stats;
  stats.count = static_cast<int>(values.size());
  if (values.empty()) return stats;
  double sum = 0, sum_squares = 0;
  for (double v : values) {
    sum += v;
    sum_squares += v * v;
  }
  stats.mean = sum / stats.count;
  stats.rms = std::sqrt(sum_squares / stats.count);
  stats.max = *std::max_element(values.begin(), values.end());
  if (stats.count > 1) {
    // Two-pass variance: Σ(v - mean)² does not cancel catastrophically like Σv² - n·mean².
    double deviations = 0;
    for (double v : values) deviations += (v - stats.mean) * (v - stats.mean);
    stats.std = std::sqrt(deviations / (stats.count - 1));
  }
  return stats;
}

}  // namespace hexcal

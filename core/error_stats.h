// Summary statistics of a list of errors (validation errors, parameter errors).
//
//   ErrorStats stats = SummarizeErrors({0.1, 0.3, 0.2});  // mean 0.2, std 0.1
#pragma once

#include <vector>

namespace hexcal {

struct ErrorStats {
  int count = 0;
  double mean = 0;
  double std = 0;  // sample standard deviation (divides by count - 1); 0 for fewer than 2 values
  double rms = 0;  // √(Σ e² / count)
  double max = 0;  // largest value
};

ErrorStats SummarizeErrors(const std::vector<double>& values);

}  // namespace hexcal

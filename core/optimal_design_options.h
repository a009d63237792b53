// When the optimal approximate designs stop: the D-optimal design of
// optimal_design.h, the S-optimal one of sigma_design.h and the working set
// both are solved on (working_set_design.h). Apart from optimal_design.h so
// that the working set, which ComputeOptimalDesign runs, need not include it.
//
//   OptimalDesignOptions options;
//   options.gap_tolerance = 1e-3;  // a coarser certificate, sooner
//   options.max_seconds = 10;
//   StatusOr<OptimalDesign> design = ComputeOptimalDesign(candidates, options);
#pragma once

namespace hexcal {

struct OptimalDesignOptions {
  double gap_tolerance = 1e-4;  // stop when max_x d(x, w) / 42 - 1 is below this
  int max_iterations = 100000;
  double max_seconds = 60;
  int threads = 0;  // variance function threads; 0: every core
};

}  // namespace hexcal

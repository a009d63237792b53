// What the two joint fits (the calibrations from pixels and from points:
// vision/pixel_calibration.h, core/point_calibration.h) are both given: the
// leg readings' σ, the screening pass's robust loss, and the solver's
// iterations and threads. Each fit's options derive from it and add what
// only that fit estimates.
//
//   PointCalibrationOptions options;  // a JointFitSettings with estimate_reflectors
//   options.leg_sigma = noise.LegStdDev();
//   std::string why;
//   if (!options.IsValid(&why)) return Status::BadInput(why);
#pragma once

#include <cmath>
#include <string>

namespace hexcal {

struct JointFitSettings {
  double leg_sigma = 0.001;  // standard deviation of a leg reading, robot unit (> 0)
  // > 0: a Cauchy loss of this many σ_L on the leg residuals, so that one
  // wrong reading cannot pull the fit (the screening pass; 0: least squares).
  double leg_cauchy_scale = 0;
  int max_iterations = 100;  // Levenberg–Marquardt iterations
  // 1: Ceres sums the cost and gradient of a multi-threaded evaluation in the
  // order its threads finish, so the result would differ in the 8th digit from
  // run to run; one thread keeps every calibration and report reproducible.
  int num_threads = 1;  // 0: every core

  bool IsValid(std::string* error) const {
    auto fail = [&](const char* message) {
      if (error) *error = message;
      return false;
    };
    if (!(leg_sigma > 0) || !std::isfinite(leg_sigma)) return fail("leg_sigma must be positive");
    if (max_iterations < 1) return fail("max_iterations must be at least 1");
    if (!(leg_cauchy_scale >= 0) || !std::isfinite(leg_cauchy_scale)) return fail("leg_cauchy_scale must be 0 or more");
    if (num_threads < 0) return fail("num_threads must be 0 (every core) or more");
    return true;
  }
};

}  // namespace hexcal

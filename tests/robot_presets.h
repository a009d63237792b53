// Robots and poses for tests: presets by name (a preset that does not load
// fails the test, not the process), perturbed "true" robots, random poses, and
// how close a calibration came to the true robot.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/candidates.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "tests/test_support.h"

namespace hexcal::testing {

inline Robot Preset(const std::string& name) {
  StatusOr<Robot> robot = LoadRobot(name);
  EXPECT_TRUE(robot.ok()) << robot.status().message();
  return robot.ok() ? *robot : Robot{};
}

// The nominal robot with every one of its 42 parameters moved uniformly within
// ±half_width (robot unit), drawn from the per-test RNG.
inline Robot PerturbedRobot(const Robot& nominal, double half_width) {
  ParameterVector p = ParametersOf(nominal);
  for (int k = 0; k < kNumParams; ++k) p[k] += Uniform(-half_width, half_width);
  return WithParameters(nominal, p);
}

// `count` feasible random poses of the robot (its sampling box), seeded.
inline std::vector<Vector6d> RandomFeasiblePoses(const Robot& robot, int count, uint64_t seed) {
  CandidateOptions options;
  options.count = count;
  options.seed = seed;
  StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
  EXPECT_TRUE(set.ok()) << set.status().message();
  return set.ok() ? set->poses : std::vector<Vector6d>{};
}

// The same over the robot's whole pose box, not its central sampling box:
// spread sets, for well-conditioned plans and accurate finite differences.
inline std::vector<Vector6d> SpreadFeasiblePoses(Robot robot, int count, uint64_t seed) {
  robot.limits.sampling_box.reset();
  return RandomFeasiblePoses(robot, count, seed);
}

// How close a calibration came to the truth: the share of the 42 parameters
// within 3σ of it, and the mean |error| (robot unit).
struct Accuracy {
  double within_3sigma = 0;
  double mean_error = 0;
};

// The errors of `fit` against `truth` in the frames the fit registered (the
// gauge, docs/session.md): the truth, simulated with the sensor at
// true_base_from_sensor and the target at true_platform_from_target, is first
// expressed in the registration's frames.
inline Accuracy AccuracyInRegisteredFrames(const CalibrationResult& fit, const Robot& truth,
                                           const Pose& true_base_from_sensor, const Pose& true_platform_from_target,
                                           const Registration& frames) {
  const Robot truth_in_frames =
      ExpressInFrames(truth, Compose(frames.base_from_camera, Inverse(true_base_from_sensor)),
                      Compose(frames.platform_from_target, Inverse(true_platform_from_target)));
  const ParameterVector error = fit.Estimates() - ParametersOf(truth_in_frames);
  const ParameterVector sigma = fit.StdDevs();
  int within = 0;
  for (int k = 0; k < kNumParams; ++k) within += std::abs(error[k]) <= 3 * sigma[k] ? 1 : 0;
  return {within / double(kNumParams), error.cwiseAbs().mean()};
}

}  // namespace hexcal::testing

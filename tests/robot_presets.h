// Robots and poses for tests: presets by name (a preset that does not load
// fails the test, not the process), perturbed "true" robots and random poses.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/candidates.h"
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

}  // namespace hexcal::testing

// Robot presets for tests: loads by name and fails the test (not the process)
// when a preset does not load.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/robot_io.h"

namespace hexcal::testing {

inline Robot Preset(const std::string& name) {
  StatusOr<Robot> robot = LoadRobot(name);
  EXPECT_TRUE(robot.ok()) << robot.status().message();
  return robot.ok() ? *robot : Robot{};
}

}  // namespace hexcal::testing

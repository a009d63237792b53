// libFuzzer target: the robot YAML parser (core/robot_io.h), and a parsed robot
// written back and parsed again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/robot_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::Robot> robot = hexcal::ParseRobotYaml(text, "fuzz.yaml");
  if (!robot.ok()) return 0;
  // A robot the parser accepts must survive its own writer.
  if (!hexcal::ParseRobotYaml(hexcal::RobotToYaml(*robot), "round-trip.yaml").ok()) std::abort();
  return 0;
}

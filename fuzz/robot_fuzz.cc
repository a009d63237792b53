// libFuzzer target: the robot YAML parser (core/robot_io.h), and a parsed robot
// written back and parsed again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>

#include "core/robot_io.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // A robot the parser accepts must survive its own writer.
  hexcal::fuzz::CheckRoundTrip(data, size, hexcal::ParseRobotYaml, hexcal::RobotToYaml);
  return 0;
}

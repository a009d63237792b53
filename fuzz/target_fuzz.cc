// libFuzzer target: the calibration target YAML parser (vision/target.h), and a
// parsed target written back and parsed again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "vision/target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  hexcal::fuzz::CheckRoundTrip(data, size, hexcal::ParseTargetYaml, hexcal::TargetToYaml);
  return 0;
}

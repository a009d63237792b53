// libFuzzer target: the calibration target YAML parser (vision/target.h), and a
// parsed target written back and parsed again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "vision/target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::Target> target = hexcal::ParseTargetYaml(text, "fuzz.yaml");
  if (!target.ok()) return 0;
  if (!hexcal::ParseTargetYaml(hexcal::TargetToYaml(*target), "round-trip.yaml").ok()) std::abort();
  return 0;
}

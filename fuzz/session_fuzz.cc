// libFuzzer target: a session's session.yaml (core/session.h), read by
// LoadSessionConfig from a session folder; a configuration it accepts is saved
// and must load again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/session.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string dir = hexcal::fuzz::ScratchDir();
  hexcal::fuzz::WriteOrDie(hexcal::SessionPaths(dir).config, data, size);
  const hexcal::StatusOr<hexcal::SessionConfig> config = hexcal::LoadSessionConfig(dir);
  if (!config.ok()) return 0;
  const std::string copy = dir + "/copy";
  std::filesystem::create_directories(copy);
  if (!hexcal::SaveSessionConfig(copy, *config).ok()) std::abort();
  if (!hexcal::LoadSessionConfig(copy).ok()) std::abort();
  return 0;
}

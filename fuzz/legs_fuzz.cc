// libFuzzer target: a session's legs.csv (core/session.h), read by
// LoadSessionLegs from a session folder whose images/ holds three images, and
// the same file through LoadLegReadings (core/csv.h). docs/hardening.md says
// how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/csv.h"
#include "core/session.h"
#include "fuzz/fuzz_support.h"

namespace {

// The seeds (fuzz/seeds/legs_*.csv) name these images.
const std::string& SessionDir() {
  static const std::string dir = [] {
    const std::string session = hexcal::fuzz::ScratchDir() + "/session";
    std::filesystem::create_directories(session + "/images");
    for (const char* image : {"view_0001.png", "view_0002.png", "view_0003.png"}) {
      hexcal::fuzz::WriteOrDie(session + "/images/" + image, nullptr, 0);
    }
    return session;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string legs = SessionDir() + "/legs.csv";
  hexcal::fuzz::WriteOrDie(legs, data, size);
  const hexcal::StatusOr<std::vector<hexcal::LegsRow>> rows = hexcal::LoadSessionLegs(SessionDir());
  if (rows.ok()) {
    for (const hexcal::LegsRow& row : *rows) {
      if (!row.legs.allFinite()) std::abort();
    }
  }
  (void)hexcal::LoadLegReadings(legs);
  return 0;
}

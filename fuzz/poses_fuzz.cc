// libFuzzer target: pose CSV files. LoadPoses reads the input from a file as
// `hexcal ik --poses` does; the CSV reader (core/csv.h) and the number parser
// behind every pose, leg and measurement file are also driven on every cell.
// docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/csv.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = hexcal::fuzz::ScratchDir() + "/poses.csv";
  hexcal::fuzz::WriteOrDie(path, data, size);
  const hexcal::StatusOr<std::vector<hexcal::Vector6d>> poses = hexcal::LoadPoses(path);
  if (poses.ok()) {
    for (const hexcal::Vector6d& pose : *poses) {
      if (!pose.allFinite()) std::abort();  // LoadPoses promises finite numbers
    }
  }
  const hexcal::StatusOr<hexcal::CsvTable> table = hexcal::ParseCsv(text, "fuzz.csv");
  if (!table.ok()) return 0;
  for (size_t row = 0; row < table->rows.size(); ++row) {
    for (size_t col = 0; col < table->header.size(); ++col) {
      const hexcal::StatusOr<double> value = hexcal::NumberAt(*table, row, static_cast<int>(col));
      // A number written by FormatNumber must read back as itself.
      if (value.ok() && *hexcal::ParseNumber(hexcal::FormatNumber(*value)) != *value) std::abort();
    }
  }
  return 0;
}

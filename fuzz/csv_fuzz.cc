// libFuzzer target: the CSV reader behind pose, leg-reading and measurement
// files (core/csv.h), then every cell through the number parser, as LoadPoses,
// LoadLegReadings and LoadMeasurements do. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::CsvTable> table = hexcal::ParseCsv(text, "fuzz.csv");
  if (!table.ok()) return 0;
  for (const char* name : {"x", "y", "z", "q1", "q2", "q3", "L1", "L6"}) {
    (void)hexcal::ColumnIndex(*table, name);
  }
  for (size_t row = 0; row < table->rows.size(); ++row) {
    for (size_t col = 0; col < table->header.size(); ++col) {
      const hexcal::StatusOr<double> value = hexcal::NumberAt(*table, row, static_cast<int>(col));
      if (value.ok()) (void)hexcal::FormatNumber(*value);
    }
  }
  return 0;
}

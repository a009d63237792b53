// libFuzzer target: measurement CSV. ParseMeasurements (core/measurements.h,
// `hexcal calibrate --measurements`), and a session's camera_poses.csv of
// camera_from_target rows with their covariance, by ParseImageMeasurementsCsv
// (vision/measure.h), the parser `hexcal calibrate --session` uses.
// docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/measurements.h"
#include "vision/measure.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<std::vector<hexcal::Measurement>> rows = hexcal::ParseMeasurements(text, "fuzz.csv");
  if (rows.ok()) {
    for (const hexcal::Measurement& row : *rows) {
      if (!row.pose.allFinite() || !row.legs.allFinite()) std::abort();
    }
  }
  const hexcal::StatusOr<std::vector<hexcal::ImageMeasurementRecord>> records =
      hexcal::ParseImageMeasurementsCsv(text, "camera_poses.csv");
  if (!records.ok()) return 0;
  for (const hexcal::ImageMeasurementRecord& record : *records) {
    if (!record.ok) continue;
    if (!record.camera_from_target.position.allFinite() || !record.camera_from_target.rotation.allFinite() ||
        !record.covariance.allFinite())
      std::abort();
  }
  return 0;
}

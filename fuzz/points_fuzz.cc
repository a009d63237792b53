// libFuzzer target: a points file (core/point_file.h, CSV or SpatialAnalyzer
// ASCII) and, from the same bytes, a reflector file; every pose of a file it
// accepts is fitted to the reflectors the sets imply (core/reflector_estimate.h,
// core/point_fit.h), which must give finite poses or an error, never a crash.
// docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/point_file.h"
#include "core/point_fit.h"
#include "core/reflector_estimate.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)hexcal::ParseReflectorFile(text, "fuzz");
  const hexcal::StatusOr<hexcal::PointSets> sets = hexcal::ParsePointFile(text, "fuzz", 0.01);
  if (!sets.ok()) return 0;
  const hexcal::StatusOr<std::vector<hexcal::NamedPoint>> reflectors = hexcal::EstimateReflectors(*sets);
  if (!reflectors.ok()) return 0;
  for (const hexcal::PointSet& set : *sets) {
    const hexcal::StatusOr<hexcal::PointFit> fit = hexcal::FitPointPose(*reflectors, set.points);
    if (fit.ok() && !(fit->pose.position.allFinite() && fit->pose.rotation.allFinite())) std::abort();
  }
  return 0;
}

// The Measure step on a folder (`hexcal measure`): camera_from_target of
// every image, with its σ and status, written to a measurements CSV
// (vision/measure.h has the per-image work; docs/vision.md).
//
//   MeasureRequest request{"camera.yaml", "aprilgrid-6x6", "images/", "measurements.csv"};
//   StatusOr<MeasureResult> result = MeasureFolder(request, hooks);
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/status.h"
#include "vision/measure.h"

namespace hexcal::workflow {

struct MeasureRequest {
  std::string camera;                          // camera file
  std::string target = kDefaultTargetName;     // target file or built-in name
  std::string images;                          // an image or a folder of images
  std::string out;                             // measurements CSV to write
  bool force = false;                          // replace an existing `out`
  MeasureOptions options;                      // detector, pose thresholds, threads
};

struct MeasureResult {
  std::string out, length_unit;              // the target's unit
  std::vector<ImageMeasurement> rows;        // one per image, file names relative to a folder
  std::map<std::string, int> counts;         // by PoseStatusName
  int ok() const;
};

// Fails (StatusKind::kFailed) when no image gives a pose; the CSV is written
// before, so that the reasons per image can be read.
StatusOr<MeasureResult> MeasureFolder(const MeasureRequest& request, const JobHooks& hooks = {});

nlohmann::json ToJson(const MeasureResult& result);
std::string FormatMeasureSummary(const MeasureResult& result);

}  // namespace hexcal::workflow

// The Measure step on a folder (`hexcal measure`): camera_from_target of
// every image, with its σ and status, written to a measurements CSV
// (vision/measure.h has the per-image work; docs/vision.md).
//
//   MeasureRequest request{"camera.yaml", "aprilgrid-6x6", "images/", "camera_poses.csv"};
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

// Loads the camera and target files, lists the images and measures them
// (MeasureFiles). Images without a pose are rows with their reason; the
// caller decides whether none at all is a failure (`hexcal measure` says so).
StatusOr<MeasureResult> MeasureFolder(const MeasureRequest& request, const JobHooks& hooks = {});

// The same on loaded inputs (the GUI's Measure all): `files` measured, their
// names made relative (file name only) and the CSV written atomically to `out`.
StatusOr<MeasureResult> MeasureFiles(const std::vector<std::string>& files, const Camera& camera,
                                     const Target& target, const MeasureOptions& options, const std::string& out,
                                     const JobHooks& hooks = {});

// When at least half of the images that show the board fit it badly
// (high_rms), what that says: the target or camera file does not describe
// the board and lens (a wrong layout, unit or model, not a bad image). "" otherwise.
std::string DiagnoseMeasurements(const MeasureResult& result);
// The same from counts of images by PoseStatusName.
std::string DiagnoseBoardFits(const std::map<std::string, int>& counts);

nlohmann::json ToJson(const MeasureResult& result);
std::string FormatMeasureSummary(const MeasureResult& result);

}  // namespace hexcal::workflow

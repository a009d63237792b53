// Camera intrinsics from a folder of target images (`hexcal intrinsics`, the
// GUI's "Intrinsics from folder…"): calibrate (vision/intrinsics.h), write the
// camera file with its fit figures and, optionally, the corner coverage picture
// and the residual field (OUT with .residuals.png); the per-corner diagnostics
// (corner_report_section.h) go into the summary and the JSON.
//
//   StatusOr<IntrinsicsOutcome> camera = CalibrateCameraFromFolder({"aprilgrid-6x6", "calib/", "camera.yaml"});
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/status.h"
#include "session/corner_residuals_file.h"
#include "vision/intrinsics.h"

namespace hexcal::workflow {

struct IntrinsicsRequest {
  std::string target = kDefaultTargetName;  // target file or built-in name
  std::string images;                       // folder of images
  std::string out;                          // camera file to write (OpenCV YAML)
  std::string coverage;                     // coverage PNG; empty: OUT with .coverage.png
  bool force = false;                       // replace an existing `out`
  IntrinsicsOptions options;
};

struct IntrinsicsOutcome {
  IntrinsicsResult result;
  std::string out, coverage;  // files written (coverage empty when not written)
  int images = 0;             // images given
  double outlier_factor = 3;  // the options' outlier_factor: a used view this many times the median is named
  // The residual field chart written beside the coverage picture; empty when
  // not written (no coverage picture, or charts cannot be drawn on this
  // thread: chart_render.h).
  std::string residuals;
};

// The used views' corners and their residuals, images named by their files.
CornerResidualTable CornerTableOf(const IntrinsicsResult& result);

StatusOr<IntrinsicsOutcome> CalibrateCameraFromFolder(const IntrinsicsRequest& request, const JobHooks& hooks = {});

// The same on loaded inputs; `coverage` may be empty (no picture).
StatusOr<IntrinsicsOutcome> CalibrateCameraFromFiles(const std::vector<std::string>& files, const Target& target,
                                                     const IntrinsicsOptions& options, const std::string& out,
                                                     const std::string& coverage, const JobHooks& hooks = {});

nlohmann::json ToJson(const IntrinsicsOutcome& outcome);
std::string FormatIntrinsicsSummary(const IntrinsicsOutcome& outcome);

}  // namespace hexcal::workflow

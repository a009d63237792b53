// results/corner_residuals.csv: every tag corner's reprojection residual at
// the calibration from pixels (vision/corner_diagnostics.h), one row per
// corner, for the report's per-corner diagnostics and for the operator's own
// plots (docs/session.md, docs/calibration.md "Per-corner diagnostics").
//
//   image,tag_id,corner,x_px,y_px,dx_px,dy_px
//   images/view_0003.png,17,2,512.25,301.5,0.031,-0.12
//
// x, y: the detected corner (pixel origin as docs/conventions.md);
// dx, dy: projected − detected.
//
//   StatusOr<CornerResidualTable> table = LoadCornerResiduals("run1/results/corner_residuals.csv");
#pragma once

#include <string>
#include <vector>

#include "core/status.h"
#include "vision/corner_diagnostics.h"

namespace hexcal::workflow {

struct CornerResidualTable {
  std::vector<std::string> images;  // names, indexed by CornerResidual::image
  std::vector<CornerResidual> corners;
};

Status SaveCornerResiduals(const std::string& path, const CornerResidualTable& table);
// Errors name the file, the line and the column (core/csv.h).
StatusOr<CornerResidualTable> LoadCornerResiduals(const std::string& path);

}  // namespace hexcal::workflow

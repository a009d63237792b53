// The per-corner diagnostics (vision/corner_diagnostics.h) as the report and
// `hexcal intrinsics` show them (docs/calibration.md, "Per-corner
// diagnostics"): the residual field, the |residual| histogram against the
// noise the fit itself shows (σ from the median, RobustAxisSigma), the worst
// corners named and where corners were seen, as an HTML section, as JSON and
// as the worst-corner lines a command prints.
//
//   html += CornerDiagnosticsSection(table, camera.width, camera.height);
//   json["corners"] = CornerDiagnosticsJson(table, camera.width, camera.height);
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "session/corner_residuals_file.h"

namespace hexcal::workflow {

constexpr int kWorstCornersShown = 10;

// "Per-corner diagnostics": the charts (inline SVG), the worst corners and
// the coverage grid; draws with Qt (session_report.h's thread rule).
std::string CornerDiagnosticsSection(const CornerResidualTable& table, double width, double height);

// {"sigma_px", "rms_px", "worst": [{image, tag_id, corner, x_px, y_px, dx_px,
// dy_px, residual_px}], "histogram": {bin_width_px, counts, expected, beyond,
// expected_beyond}, "coverage": {cols, rows, counts (row-major), empty_cells}}.
nlohmann::json CornerDiagnosticsJson(const CornerResidualTable& table, double width, double height);

// One line of the figures: "3456 corners, RMS 0.0188 px, sigma 0.0127 px
// (from the median); 85 at 3 sigma or more (noise alone: 38.5); 11 of 48
// image cells without a corner".
std::string FormatCornerFigures(const CornerResidualTable& table, double width, double height);

// The worst corners as lines: "  12.png tag 17 corner 2 at (512.2, 301.5): 0.84 px (6.1 sigma)".
std::string FormatWorstCorners(const CornerResidualTable& table, int k = kWorstCornersShown);

}  // namespace hexcal::workflow

// The figures of the per-corner diagnostics (vision/corner_diagnostics.h), as
// charts/ specs for the session report and its PNGs (docs/calibration.md,
// "Per-corner diagnostics"). Image coordinates: x to the right, y (rows)
// downwards as in the image, over the image's frame.
//
//   html += ChartSvgElement(ResidualFieldChart(corners, camera.width, camera.height));
#pragma once

#include <vector>

#include "charts/chart_spec.h"
#include "vision/corner_diagnostics.h"

namespace hexcal::workflow {

// The arrow scale of the residual field: the 1, 2 or 5 × 10^k nearest below
// the factor that draws the 95th-percentile |residual| as 4 % of the image
// width (a few arrows of outliers may be longer). 1 when every residual is 0.
double ResidualArrowScale(const std::vector<CornerResidual>& corners, double width);

// One arrow per corner from the detected corner along scale × (projected −
// detected), with a head, in the image frame.
charts::ChartSpec ResidualFieldChart(const std::vector<CornerResidual>& corners, double width, double height);

// Corners per |residual| bin, beside the Rayleigh counts noise of h.sigma
// gives, the bins past 6σ as one bar.
charts::ChartSpec ResidualHistogramChart(const ResidualHistogram& h);

// Every corner's position (a small +) in the image frame, with the coverage grid's cells.
charts::ChartSpec CoverageChart(const std::vector<CornerResidual>& corners, const CoverageGrid& grid);

}  // namespace hexcal::workflow

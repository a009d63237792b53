// What a calibration from pixels (vision/pixel_calibration.h) adds to
// results/report.json: the fit's residuals, the camera and target quantities
// it estimated with their σ, what it could hardly separate, and the two-stage
// calibration it started from, for the comparison (docs/calibration.md,
// "Calibration from pixels").
//
//   if (report.from_pixels) for (const PixelEstimateSummary& e : report.from_pixels->estimated) Show(e);
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "session/json_fields.h"

namespace hexcal::workflow {

struct PixelEstimateSummary {
  std::string name;  // fx, fy, cx, cy (pixels), target_scale (1 = as printed)
  double file_value = 0, estimate = 0, sigma = 0;
};

struct PixelCorrelationSummary {
  std::string first, second;
  double correlation = 0;
};

// The two-stage calibration the fit started from: its held-out errors (when
// images were held out) and its parameters' mean σ.
struct TwoStageComparison {
  std::optional<double> held_out_position_rms;         // robot unit
  std::optional<double> held_out_orientation_rms_deg;  // degrees
  double mean_parameter_sigma = 0;                     // robot unit
};

struct PixelFitSummary {
  int images = 0, corners = 0, leg_rows = 0;
  double reprojection_rms_px = 0;  // per corner, both axes
  double leg_residual_rms = 0;     // robot unit
  double variance_factor = 0;
  int iterations = 0;
  std::vector<PixelEstimateSummary> estimated;
  std::vector<PixelCorrelationSummary> strong_correlations;
  TwoStageComparison two_stage;
  double mean_parameter_sigma = 0;  // robot unit, of this fit
};

nlohmann::json ToJson(const PixelFitSummary& summary);
// The lines `calibrate --session --from-pixels` prints (`unit`: the robot's length unit).
std::string FormatPixelFitSummary(const PixelFitSummary& summary, const std::string& unit);
// Reads what ToJson wrote; problems go to `fields`' status.
PixelFitSummary PixelFitSummaryFromJson(JsonFields fields);

}  // namespace hexcal::workflow

#include "session/pixel_fit_summary.h"

#include <cstdio>

namespace hexcal::workflow {
namespace {

nlohmann::json Optional(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::string Printf(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b, c, d);
  return text;
}

}  // namespace

std::string FormatPixelFitSummary(const PixelFitSummary& s, const std::string& unit) {
  std::string out = "from pixels: " + std::to_string(s.images) + " images, " + std::to_string(s.corners) +
                    " corners, reprojection RMS " + Printf("%.3g px", s.reprojection_rms_px) + ", leg residual RMS " +
                    Printf("%.3g ", s.leg_residual_rms) + unit + ", variance factor " +
                    Printf("%.3g", s.variance_factor) + ", " + std::to_string(s.iterations) + " iterations\n";
  for (const PixelEstimateSummary& e : s.estimated) {
    const double change = 100 * (e.estimate - e.file_value) / e.file_value;
    out += "  " + e.name + Printf(" %.6g -> %.6g ± %.2g (%+.3f %% of the file's)\n", e.file_value, e.estimate, e.sigma,
                                  change);
  }
  out += "  mean parameter sigma " + Printf("%.4g ", s.mean_parameter_sigma) + unit + " (two-stage " +
         Printf("%.4g", s.two_stage.mean_parameter_sigma) + ")\n";
  for (const PixelCorrelationSummary& c : s.strong_correlations)
    out += "  hardly separable: " + c.first + " ~ " + c.second + Printf(" (correlation %.3f)\n", c.correlation);
  if (s.two_stage.held_out_position_rms) {
    out += "  two-stage held-out validation: position RMS " + Printf("%.4g ", *s.two_stage.held_out_position_rms) +
           unit + Printf(", orientation RMS %.4g deg\n", s.two_stage.held_out_orientation_rms_deg.value_or(0));
  }
  return out;
}

nlohmann::json ToJson(const PixelFitSummary& summary) {
  nlohmann::json estimated = nlohmann::json::array();
  for (const PixelEstimateSummary& e : summary.estimated) {
    estimated.push_back({{"name", e.name}, {"file_value", e.file_value}, {"estimate", e.estimate}, {"sigma", e.sigma}});
  }
  nlohmann::json correlations = nlohmann::json::array();
  for (const PixelCorrelationSummary& c : summary.strong_correlations) {
    correlations.push_back({{"first", c.first}, {"second", c.second}, {"correlation", c.correlation}});
  }
  const TwoStageComparison& two = summary.two_stage;
  return {{"images", summary.images},
          {"corners", summary.corners},
          {"leg_rows", summary.leg_rows},
          {"reprojection_rms_px", summary.reprojection_rms_px},
          {"leg_residual_rms", summary.leg_residual_rms},
          {"variance_factor", summary.variance_factor},
          {"iterations", summary.iterations},
          {"mean_parameter_sigma", summary.mean_parameter_sigma},
          {"estimated", estimated},
          {"strong_correlations", correlations},
          {"two_stage",
           {{"held_out_position_rms", Optional(two.held_out_position_rms)},
            {"held_out_orientation_rms_deg", Optional(two.held_out_orientation_rms_deg)},
            {"mean_parameter_sigma", two.mean_parameter_sigma}}}};
}

PixelFitSummary PixelFitSummaryFromJson(JsonFields fields) {
  PixelFitSummary summary;
  summary.images = fields.Int("images");
  summary.corners = fields.Int("corners");
  summary.leg_rows = fields.Int("leg_rows");
  summary.reprojection_rms_px = fields.Number("reprojection_rms_px");
  summary.leg_residual_rms = fields.Number("leg_residual_rms");
  summary.variance_factor = fields.Number("variance_factor");
  summary.iterations = fields.Int("iterations");
  summary.mean_parameter_sigma = fields.Number("mean_parameter_sigma");
  for (JsonFields e : fields.Array("estimated")) {
    summary.estimated.push_back({e.String("name"), e.Number("file_value"), e.Number("estimate"), e.Number("sigma")});
  }
  for (JsonFields c : fields.Array("strong_correlations")) {
    summary.strong_correlations.push_back({c.String("first"), c.String("second"), c.Number("correlation")});
  }
  JsonFields two = fields.Object("two_stage");
  summary.two_stage = {two.OptionalNumber("held_out_position_rms"), two.OptionalNumber("held_out_orientation_rms_deg"),
                       two.Number("mean_parameter_sigma")};
  return summary;
}

}  // namespace hexcal::workflow

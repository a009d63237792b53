#include "session/point_fit_summary.h"

#include <cstdio>

namespace hexcal::workflow {
namespace {

nlohmann::json Optional(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json Triple(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d TripleOf(JsonFields& fields, const std::string& key) {
  const std::vector<double> v = fields.Numbers(key, 3);
  return v.size() == 3 ? Eigen::Vector3d(v[0], v[1], v[2]) : Eigen::Vector3d::Zero();
}

std::string Printf(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char text[200];
  std::snprintf(text, sizeof text, format, a, b, c, d);
  return text;
}

}  // namespace

std::string FormatPointFitSummary(const PointFitSummary& s, const std::string& unit) {
  std::string out = "from points: " + std::to_string(s.poses) + " poses, " + std::to_string(s.points) +
                    " points, point residual RMS " + Printf("%.3g ", s.point_rms) + unit + ", leg residual RMS " +
                    Printf("%.3g ", s.leg_residual_rms) + unit + ", variance factor " +
                    Printf("%.3g", s.variance_factor) + ", " + std::to_string(s.iterations) + " iterations\n";
  out += "  identifiable: rank " + std::to_string(s.rank) + " of " + std::to_string(s.unknowns) +
         " unknowns, smallest/largest eigenvalue " + Printf("%.3g", s.eigenvalue_ratio) + "\n";
  if (s.reflectors_estimated) {
    out += "  reflectors estimated (" + std::string(s.reflectors_from_file ? "the file's" : "the poses' estimate") +
           " -> fitted ± sigma, " + unit + "):\n";
    for (const ReflectorSummary& r : s.reflectors) {
      const Eigen::Vector3d change = r.estimate - r.given;
      out += "    " + r.name + Printf(" moved %.3g (x %+.3g ± %.2g, ", change.norm(), change.x(), r.sigma.x()) +
             Printf("y %+.3g ± %.2g, z %+.3g ± %.2g)\n", change.y(), r.sigma.y(), change.z(), r.sigma.z());
    }
    out += Printf("  reflector shape scale %.6f ± %.2g of the given one\n", s.reflector_scale, s.reflector_scale_sigma);
  } else {
    out += "  reflectors kept as given\n";
  }
  out += "  mean parameter sigma " + Printf("%.4g ", s.mean_parameter_sigma) + unit + " (two-stage " +
         Printf("%.4g", s.two_stage.mean_parameter_sigma) + ")\n";
  if (s.two_stage.held_out_position_rms) {
    out += "  two-stage held-out validation: position RMS " + Printf("%.4g ", *s.two_stage.held_out_position_rms) +
           unit + Printf(", orientation RMS %.4g deg\n", s.two_stage.held_out_orientation_rms_deg.value_or(0));
  }
  return out;
}

nlohmann::json ToJson(const PointFitSummary& summary) {
  nlohmann::json reflectors = nlohmann::json::array();
  for (const ReflectorSummary& r : summary.reflectors) {
    reflectors.push_back(
        {{"name", r.name}, {"given", Triple(r.given)}, {"estimate", Triple(r.estimate)}, {"sigma", Triple(r.sigma)}});
  }
  const TwoStageComparison& two = summary.two_stage;
  return {{"poses", summary.poses},
          {"points", summary.points},
          {"leg_rows", summary.leg_rows},
          {"point_rms", summary.point_rms},
          {"leg_residual_rms", summary.leg_residual_rms},
          {"variance_factor", summary.variance_factor},
          {"iterations", summary.iterations},
          {"reflectors_estimated", summary.reflectors_estimated},
          {"reflectors_from_file", summary.reflectors_from_file},
          {"reflectors", reflectors},
          {"reflector_scale", summary.reflector_scale},
          {"reflector_scale_sigma", summary.reflector_scale_sigma},
          {"largest_reflector_correlation", summary.largest_reflector_correlation},
          {"identifiability",
           {{"unknowns", summary.unknowns}, {"rank", summary.rank}, {"eigenvalue_ratio", summary.eigenvalue_ratio}}},
          {"mean_parameter_sigma", summary.mean_parameter_sigma},
          {"two_stage",
           {{"held_out_position_rms", Optional(two.held_out_position_rms)},
            {"held_out_orientation_rms_deg", Optional(two.held_out_orientation_rms_deg)},
            {"mean_parameter_sigma", two.mean_parameter_sigma}}}};
}

PointFitSummary PointFitSummaryFromJson(JsonFields fields) {
  PointFitSummary summary;
  summary.poses = fields.Int("poses");
  summary.points = fields.Int("points");
  summary.leg_rows = fields.Int("leg_rows");
  summary.point_rms = fields.Number("point_rms");
  summary.leg_residual_rms = fields.Number("leg_residual_rms");
  summary.variance_factor = fields.Number("variance_factor");
  summary.iterations = fields.Int("iterations");
  summary.reflectors_estimated = fields.Bool("reflectors_estimated");
  summary.reflectors_from_file = fields.Bool("reflectors_from_file");
  for (JsonFields r : fields.Array("reflectors"))
    summary.reflectors.push_back(
        {r.String("name"), TripleOf(r, "given"), TripleOf(r, "estimate"), TripleOf(r, "sigma")});
  summary.reflector_scale = fields.Number("reflector_scale");
  summary.reflector_scale_sigma = fields.Number("reflector_scale_sigma");
  summary.largest_reflector_correlation = fields.Number("largest_reflector_correlation");
  JsonFields identifiability = fields.Object("identifiability");
  summary.unknowns = identifiability.Int("unknowns");
  summary.rank = identifiability.Int("rank");
  summary.eigenvalue_ratio = identifiability.Number("eigenvalue_ratio");
  summary.mean_parameter_sigma = fields.Number("mean_parameter_sigma");
  JsonFields two = fields.Object("two_stage");
  summary.two_stage = {two.OptionalNumber("held_out_position_rms"), two.OptionalNumber("held_out_orientation_rms_deg"),
                       two.Number("mean_parameter_sigma")};
  return summary;
}

}  // namespace hexcal::workflow

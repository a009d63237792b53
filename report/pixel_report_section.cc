#include "report/pixel_report_section.h"

#include <cmath>
#include <cstdio>

#include "session/results_files.h"

namespace hexcal::workflow {
namespace {

// 4 significant digits; names in the report are hexcal's own (no escaping needed).
std::string G4(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string EstimatesTable(const PixelFitSummary& fit) {
  if (fit.estimated.empty()) return "<p>The camera file's intrinsics and the target's printed size were kept.</p>\n";
  std::string html = "<table><tr><th>quantity</th><th>file</th><th>estimate</th><th>&sigma;</th><th>change</th></tr>\n";
  for (const PixelEstimateSummary& e : fit.estimated) {
    const double change = 100 * (e.estimate - e.file_value) / e.file_value;
    char cells[256];
    std::snprintf(cells, sizeof cells, "<td>%.7g</td><td>%.7g</td><td>%.2g</td><td>%+.3f %%</td>", e.file_value,
                  e.estimate, e.sigma, change);
    html += "<tr><td>" + e.name + "</td>" + cells + "</tr>\n";
  }
  return html + "</table>\n";
}

std::string Comparison(const PixelFitSummary& fit, const CalibrationReport& report) {
  const std::string unit = report.length_unit;
  std::string html = "<p>Mean parameter &sigma;: " + G4(fit.mean_parameter_sigma) + " " + unit +
                     " (two-stage: " + G4(fit.two_stage.mean_parameter_sigma) + " " + unit + ").";
  if (fit.two_stage.held_out_position_rms && report.validation) {
    html += " Held-out position RMS: " + G4(report.validation->after.position_rms) + " " + unit +
            " (two-stage: " + G4(*fit.two_stage.held_out_position_rms) + " " + unit + ").";
  }
  return html + "</p>\n";
}

std::string ReflectorTable(const PointFitSummary& fit, const std::string& unit) {
  if (!fit.reflectors_estimated)
    return "<p>The reflectors were kept as " + std::string(fit.reflectors_from_file ? "the reflector file gives them" : "estimated from the poses") + ".</p>\n";
  std::string html = "<table><tr><th>reflector</th><th>moved (" + unit + ")</th><th>x &plusmn; &sigma;</th>"
                     "<th>y &plusmn; &sigma;</th><th>z &plusmn; &sigma;</th></tr>\n";
  for (const ReflectorSummary& r : fit.reflectors) {
    const Eigen::Vector3d change = r.estimate - r.given;
    char cells[300];
    std::snprintf(cells, sizeof cells, "<td>%.3g</td><td>%+.3g &plusmn; %.2g</td><td>%+.3g &plusmn; %.2g</td>"
                  "<td>%+.3g &plusmn; %.2g</td>", change.norm(), change.x(), r.sigma.x(), change.y(), r.sigma.y(),
                  change.z(), r.sigma.z());
    html += "<tr><td>" + r.name + "</td>" + cells + "</tr>\n";
  }
  return html + "</table><p>Changes from the " + (fit.reflectors_from_file ? "reflector file" : "estimate from the poses") +
         " in its frame (" + ResultsName(kFittedReflectors) + "); the shape's size is " + G4(fit.reflector_scale) +
         " &plusmn; " + G4(fit.reflector_scale_sigma) + " of the given one.</p>\n";
}

std::string PointsMethodSection(const CalibrationReport& report) {
  if (!report.from_points) {
    return "<h2>Calibration</h2><p>Two-stage: each pose fitted to its points (weighted, with its covariance), "
           "the tracker and reflector frames registered, the legs fitted to the poses (calibrate --session "
           "--two-stage, or the calibration from points failed: see the run's warning).</p>\n";
  }
  const PointFitSummary& fit = *report.from_points;
  std::string html = "<h2>Calibration from points</h2><p>The 42 parameters" +
                     std::string(fit.reflectors_estimated ? " and the reflectors' positions" : "") + " fitted to " +
                     std::to_string(fit.points) + " points of " + std::to_string(fit.poses) + " poses and " +
                     std::to_string(fit.leg_rows) + " leg readings: point residual RMS " + G4(fit.point_rms) + " " +
                     report.length_unit + ", leg residual RMS " + G4(fit.leg_residual_rms) + " " +
                     report.length_unit + ", variance factor " + G4(fit.variance_factor) + ", " +
                     std::to_string(fit.iterations) + " iterations. Identifiable: rank " + std::to_string(fit.rank) +
                     " of " + std::to_string(fit.unknowns) + " unknowns, smallest/largest eigenvalue of the scaled "
                     "information " + G4(fit.eigenvalue_ratio) + ".</p>\n";
  html += ReflectorTable(fit, report.length_unit);
  const std::string unit = report.length_unit;
  html += "<p>Mean parameter &sigma;: " + G4(fit.mean_parameter_sigma) + " " + unit + " (two-stage: " +
          G4(fit.two_stage.mean_parameter_sigma) + " " + unit + ").";
  if (fit.two_stage.held_out_position_rms && report.validation) {
    html += " Held-out position RMS: " + G4(report.validation->after.position_rms) + " " + unit +
            " (two-stage: " + G4(*fit.two_stage.held_out_position_rms) + " " + unit + ").";
  }
  return html + "</p>\n";
}

}  // namespace

std::string CalibrationMethodSection(const CalibrationReport& report) {
  if (report.instrument == Instrument::kPoints) return PointsMethodSection(report);
  if (!report.from_pixels) {
    return "<h2>Calibration</h2><p>Two-stage: the legs fitted to the board poses (calibrate --session "
           "--two-stage, or the calibration from pixels failed: see the run's warning).</p>\n";
  }
  const PixelFitSummary& fit = *report.from_pixels;
  std::string html = "<h2>Calibration from pixels</h2><p>The 42 parameters fitted to " + std::to_string(fit.corners) +
                     " tag corners of " + std::to_string(fit.images) + " images and " + std::to_string(fit.leg_rows) +
                     " leg readings: reprojection RMS " + G4(fit.reprojection_rms_px) + " px, leg residual RMS " +
                     G4(fit.leg_residual_rms) + " " + report.length_unit + ", variance factor " +
                     G4(fit.variance_factor) + ", " + std::to_string(fit.iterations) + " iterations.</p>\n";
  html += EstimatesTable(fit);
  for (const PixelCorrelationSummary& c : fit.strong_correlations) {
    html += "<p>Hardly separable: " + c.first + " and " + c.second + " (correlation " + G4(c.correlation) +
            "): estimate fewer camera quantities, or add poses at other depths.</p>\n";
  }
  return html + Comparison(fit, report);
}

}  // namespace hexcal::workflow

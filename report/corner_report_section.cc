#include "report/corner_report_section.h"

#include <cmath>
#include <cstdio>

#include "charts/chart_render.h"
#include "core/csv.h"
#include "report/corner_charts.h"
#include "report/html_text.h"
#include "session/results_files.h"

namespace hexcal::workflow {
namespace {

constexpr int kHistogramBins = 12;  // of σ/2 each, to 6σ: labels that fit the chart

std::string Pixel(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

std::string Svg(const charts::ChartSpec& spec) {
  StatusOr<std::string> svg = charts::ChartSvgElement(spec);
  return svg.ok() ? *svg + "\n" : "<p>Chart not drawn: " + HtmlEscape(svg.status().message()) + "</p>\n";
}

double Rms(const std::vector<CornerResidual>& corners) {
  double sum = 0;
  for (const CornerResidual& c : corners) sum += c.residual.squaredNorm();
  return corners.empty() ? 0 : std::sqrt(sum / static_cast<double>(corners.size()));
}

std::string WorstTable(const CornerResidualTable& table, double sigma) {
  std::string html =
      "<table><tr><th>image</th><th>tag</th><th>corner</th><th>x (px)</th><th>y (px)</th><th>dx (px)</th>"
      "<th>dy (px)</th><th>|residual| (px)</th><th>in &sigma;</th></tr>\n";
  for (const CornerResidual& c : WorstCorners(table.corners, kWorstCornersShown)) {
    html += "<tr><td>" + HtmlEscape(table.images[static_cast<size_t>(c.image)]) + "</td><td>" +
            std::to_string(c.tag_id) + "</td><td>" + std::to_string(c.corner) + "</td><td>" + Pixel(c.observed.x()) +
            "</td><td>" + Pixel(c.observed.y()) + "</td><td>" + FormatSignificant(c.residual.x()) + "</td><td>" +
            FormatSignificant(c.residual.y()) + "</td><td>" + FormatSignificant(c.residual.norm()) + "</td><td>" +
            (sigma > 0 ? FormatSignificant(c.residual.norm() / sigma) : "–") + "</td></tr>\n";
  }
  return html + "</table>\n";
}

// The grid's counts as a table laid out like the image; empty cells red.
std::string CoverageTable(const CoverageGrid& grid) {
  std::string html = "<table>\n";
  for (int r = 0; r < grid.rows; ++r) {
    html += "<tr>";
    for (int c = 0; c < grid.cols; ++c) {
      const int n = grid.At(r, c);
      html += std::string("<td style=\"min-width:3em;text-align:center") + (n == 0 ? ";background:#f4c7c3" : "") +
              "\">" + std::to_string(n) + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

// The tail the linear histogram hides: corners at 3σ and more, and how many
// noise of σ alone puts there.
struct Tail {
  int observed = 0;
  double expected = 0;
};

Tail TailOf(const std::vector<CornerResidual>& corners, double sigma) {
  Tail tail;
  for (const CornerResidual& c : corners) tail.observed += c.residual.norm() >= 3 * sigma;
  tail.expected = static_cast<double>(corners.size()) * RayleighFraction(3 * sigma, INFINITY, sigma);
  return tail;
}

std::string TailText(const std::vector<CornerResidual>& corners, double sigma) {
  const Tail tail = TailOf(corners, sigma);
  return "Corners at 3&sigma; or more: " + std::to_string(tail.observed) +
         " (noise of &sigma; alone: " + FormatSignificant(tail.expected) + ").";
}

}  // namespace

std::string CornerDiagnosticsSection(const CornerResidualTable& table, double width, double height) {
  if (table.corners.empty()) return "";
  const double sigma = RobustAxisSigma(table.corners);
  const CoverageGrid grid = CountCorners(table.corners, width, height);
  std::string html =
      "<h2>Per-corner diagnostics</h2><p>Every tag corner of the calibration from pixels (" +
      std::to_string(table.corners.size()) + " corners of " + std::to_string(table.images.size()) + " images, " +
      ResultsName(kCornerResiduals) + "): residual = projected &minus; detected. RMS " +
      FormatSignificant(Rms(table.corners)) + " px; the fit's own noise, from the median |residual|, &sigma; = " +
      FormatSignificant(sigma) +
      " px per axis. A pattern in the field (arrows that turn with the radius, or all one way) is a camera-model "
      "error, not noise; long single arrows are bad detections, named below.</p>\n";
  html += Svg(ResidualFieldChart(table.corners, width, height));
  if (sigma > 0) {
    html += Svg(ResidualHistogramChart(HistogramOfResiduals(table.corners, sigma, kHistogramBins)));
    html += "<p>" + TailText(table.corners, sigma) + "</p>\n";
  }
  html += "<h3>Worst corners</h3>\n" + WorstTable(table, sigma);
  html += "<h3>Coverage</h3><p>Corners per cell of an " + std::to_string(grid.cols) + " &times; " +
          std::to_string(grid.rows) +
          " grid over the image; the distortion is only measured where corners were "
          "seen (" +
          std::to_string(grid.EmptyCells()) + " empty cells, red).</p>\n";
  return html + Svg(CoverageChart(table.corners, grid)) + CoverageTable(grid);
}

nlohmann::json CornerDiagnosticsJson(const CornerResidualTable& table, double width, double height) {
  const double sigma = RobustAxisSigma(table.corners);
  nlohmann::json worst = nlohmann::json::array();
  for (const CornerResidual& c : WorstCorners(table.corners, kWorstCornersShown)) {
    worst.push_back({{"image", table.images[static_cast<size_t>(c.image)]},
                     {"tag_id", c.tag_id},
                     {"corner", c.corner},
                     {"x_px", c.observed.x()},
                     {"y_px", c.observed.y()},
                     {"dx_px", c.residual.x()},
                     {"dy_px", c.residual.y()},
                     {"residual_px", c.residual.norm()}});
  }
  nlohmann::json histogram;  // null when every residual is 0
  if (sigma > 0) {
    const ResidualHistogram h = HistogramOfResiduals(table.corners, sigma, kHistogramBins);
    histogram = {{"bin_width_px", h.bin_width},
                 {"counts", h.counts},
                 {"expected", h.expected},
                 {"beyond", h.beyond},
                 {"expected_beyond", h.expected_beyond}};
  }
  const CoverageGrid grid = CountCorners(table.corners, width, height);
  return {{"corners", table.corners.size()},
          {"sigma_px", sigma},
          {"rms_px", Rms(table.corners)},
          {"worst", worst},
          {"histogram", histogram},
          {"coverage",
           {{"cols", grid.cols}, {"rows", grid.rows}, {"counts", grid.counts}, {"empty_cells", grid.EmptyCells()}}}};
}

std::string FormatCornerFigures(const CornerResidualTable& table, double width, double height) {
  const double sigma = RobustAxisSigma(table.corners);
  const Tail tail = TailOf(table.corners, sigma);
  const CoverageGrid grid = CountCorners(table.corners, width, height);
  return std::to_string(table.corners.size()) + " corners, RMS " + FormatSignificant(Rms(table.corners)) +
         " px, sigma " + FormatSignificant(sigma) + " px (from the median); " + std::to_string(tail.observed) +
         " at 3 sigma or more (noise alone: " + FormatSignificant(tail.expected) + "); " +
         std::to_string(grid.EmptyCells()) + " of " + std::to_string(grid.cols * grid.rows) +
         " image cells without a corner";
}

std::string FormatWorstCorners(const CornerResidualTable& table, int k) {
  const double sigma = RobustAxisSigma(table.corners);
  std::string text;
  for (const CornerResidual& c : WorstCorners(table.corners, k)) {
    char line[160];
    std::snprintf(line, sizeof line, " tag %d corner %d at (%.1f, %.1f): %.3g px", c.tag_id, c.corner, c.observed.x(),
                  c.observed.y(), c.residual.norm());
    text += "  " + table.images[static_cast<size_t>(c.image)] + line;
    if (sigma > 0) text += " (" + FormatSignificant(c.residual.norm() / sigma) + " sigma)";
    text += "\n";
  }
  return text;
}

}  // namespace hexcal::workflow

#include "report/corner_charts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/csv.h"

namespace hexcal::workflow {
namespace {

using charts::ChartPoint;

// An arrow scale: "1000", not "1e+03".
std::string ScaleText(double scale) {
  char text[32];
  std::snprintf(text, sizeof text, scale >= 1 ? "%.0f" : "%.3g", scale);
  return text;
}

// A chart as wide as the report's and as tall as the image's aspect needs
// (the plot area is about 130 px narrower than the chart and 150 px lower).
charts::ChartSpec ImageFrameChart(const std::string& title, double width, double height) {
  charts::ChartSpec spec;
  spec.title = title;
  spec.x = charts::LinearAxis("x (px)");
  spec.y = charts::LinearAxis("y (px), rows downwards");
  spec.y.reversed = true;
  spec.width = 760;
  spec.height = static_cast<int>(std::lround(630 * height / width)) + 150;
  spec.series.push_back(
      charts::PolylineSeries("image frame", {{{0, 0}, {width, 0}, {width, height}, {0, height}, {0, 0}}}, true));
  return spec;
}

// Tail to tip and the two barbs of a head, 30 % of the arrow long at ±25°.
std::vector<ChartPoint> Arrow(const Eigen::Vector2d& tail, const Eigen::Vector2d& vector) {
  const Eigen::Vector2d tip = tail + vector, back = -0.3 * vector;
  const double c = std::cos(25 * M_PI / 180), s = std::sin(25 * M_PI / 180);
  const Eigen::Vector2d left(c * back.x() - s * back.y(), s * back.x() + c * back.y());
  const Eigen::Vector2d right(c * back.x() + s * back.y(), -s * back.x() + c * back.y());
  return {{tail.x(), tail.y()},
          {tip.x(), tip.y()},
          {tip.x() + left.x(), tip.y() + left.y()},
          {tip.x(), tip.y()},
          {tip.x() + right.x(), tip.y() + right.y()}};
}

}  // namespace

double ResidualArrowScale(const std::vector<CornerResidual>& corners, double width) {
  std::vector<double> norms;
  for (const CornerResidual& c : corners) norms.push_back(c.residual.norm());
  if (norms.empty()) return 1;
  const size_t k = static_cast<size_t>(0.95 * static_cast<double>(norms.size() - 1));
  std::nth_element(norms.begin(), norms.begin() + k, norms.end());
  if (!(norms[k] > 0)) return 1;
  const double raw = 0.04 * width / norms[k];
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double ratio = raw / power;
  return (ratio >= 5 ? 5 : ratio >= 2 ? 2 : 1) * power;
}

charts::ChartSpec ResidualFieldChart(const std::vector<CornerResidual>& corners, double width, double height) {
  const double scale = ResidualArrowScale(corners, width);
  charts::ChartSpec spec =
      ImageFrameChart("Reprojection residuals (projected − detected), arrows × " + ScaleText(scale), width, height);
  std::vector<std::vector<ChartPoint>> arrows;
  for (const CornerResidual& c : corners) arrows.push_back(Arrow(c.observed, scale * c.residual));
  spec.series.push_back(charts::PolylineSeries(std::to_string(corners.size()) + " corners", arrows));
  return spec;
}

charts::ChartSpec ResidualHistogramChart(const ResidualHistogram& h) {
  charts::ChartSpec spec;
  spec.title = "|residual| against noise of σ = " + FormatSignificant(h.sigma) + " px per axis (Rayleigh)";
  // Bins labelled by their start in σ, halves as "½": Qt elides longer labels under a dozen bars.
  std::vector<std::string> bins;
  for (size_t b = 0; b <= h.counts.size(); ++b) {
    const double start = std::round(1e6 * static_cast<double>(b) * h.bin_width / h.sigma) / 1e6;
    const double whole = std::floor(start), rest = start - whole;
    std::string label = rest == 0     ? FormatSignificant(whole)
                        : rest == 0.5 ? (whole > 0 ? FormatSignificant(whole) : "") + "½"
                                      : FormatSignificant(start);
    bins.push_back(b == h.counts.size() ? "≥" + label : label);
  }
  spec.x = charts::CategoryAxis("|residual| from, in σ = " + FormatSignificant(h.sigma) + " px", bins);
  spec.y = charts::LinearAxis("corners");
  std::vector<double> observed(h.counts.begin(), h.counts.end()), expected = h.expected;
  observed.push_back(h.beyond);
  expected.push_back(h.expected_beyond);
  spec.series = {charts::BarSeries("observed", observed), charts::BarSeries("noise of σ alone", expected)};
  return spec;
}

charts::ChartSpec CoverageChart(const std::vector<CornerResidual>& corners, const CoverageGrid& grid) {
  charts::ChartSpec spec = ImageFrameChart("Where corners were detected: " + std::to_string(grid.EmptyCells()) +
                                               " of " + std::to_string(grid.cols * grid.rows) + " cells empty",
                                           grid.width, grid.height);
  std::vector<std::vector<ChartPoint>> lines;
  for (int c = 1; c < grid.cols; ++c)
    lines.push_back({{c * grid.width / grid.cols, 0}, {c * grid.width / grid.cols, grid.height}});
  for (int r = 1; r < grid.rows; ++r)
    lines.push_back({{0, r * grid.height / grid.rows}, {grid.width, r * grid.height / grid.rows}});
  spec.series.push_back(charts::PolylineSeries("cells", lines, true));
  // A small + per corner: one path, where thousands of scatter markers would be megabytes of SVG.
  const double arm = 0.004 * grid.width;
  std::vector<std::vector<ChartPoint>> marks;
  for (const CornerResidual& c : corners) {
    const double x = c.observed.x(), y = c.observed.y();
    marks.push_back({{x - arm, y}, {x + arm, y}});
    marks.push_back({{x, y - arm}, {x, y + arm}});
  }
  spec.series.push_back(charts::PolylineSeries(std::to_string(corners.size()) + " corners", marks));
  return spec;
}

}  // namespace hexcal::workflow

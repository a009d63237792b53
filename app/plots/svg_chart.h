// Small charts as standalone SVG text, with no dependency beyond the standard
// library: the figures of `hexcal simulate --plots` (paper Figs. 14 and 15)
// and, later, of the HTML report. png_render.h turns the SVG into a PNG.
//
//   ChartOptions options;
//   options.title = "Parameter error";
//   options.y_label = "|P_est - P_true| (cm)";
//   options.log_y = true;
//   std::string svg = BarChartSvg(options, {{"before", 0.25, 0.15}, {"random", 0.04, 0.038}});
//   std::string svg2 = LineChartSvg(options, {{"random", {8, 9, 10}, {0.2, 0.1, 0.08}}});
#pragma once

#include <string>
#include <vector>

namespace hexcal::plots {

struct ChartOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  bool log_y = false;  // logarithmic y axis; values <= 0 are drawn at the axis bottom
  int width = 760;     // pixels
  int height = 460;    // pixels
};

// One bar: its height and a symmetric error bar (0 for none).
struct Bar {
  std::string label;
  double value = 0;
  double error = 0;
};

struct LineSeries {
  std::string name;
  std::vector<double> x;
  std::vector<double> y;  // same size as x
};

// Bars in the given order, each labelled under the axis and with its value above it.
std::string BarChartSvg(const ChartOptions& options, const std::vector<Bar>& bars);
// One polyline with markers per series, a shared x axis, and a legend.
std::string LineChartSvg(const ChartOptions& options, const std::vector<LineSeries>& series);

// Tick positions for a linear axis over [lo, hi]: 1, 2 or 5 times a power of ten, about `count` of them.
std::vector<double> LinearTicks(double lo, double hi, int count = 6);

}  // namespace hexcal::plots

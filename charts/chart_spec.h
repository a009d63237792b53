// What a chart shows, as plain data: the one description that the GUI's live
// charts (qt_chart.h), the HTML report's inline SVG and the PNG/SVG files of
// `hexcal simulate --plots` (chart_render.h) are all drawn from. No Qt here, so
// the figure definitions (figures.h) and their tests are plain C++.
//
// A chart is either an x-y chart (line, polyline and scatter series over numeric axes) or
// a bar chart (bar series, one value per category of the x axis, optionally
// with a symmetric error bar each). ComputeRanges() gives the axes: every data
// point lies inside them, negative values and error bars included.
//
//   ChartSpec spec;
//   spec.title = "Calibrated minus nominal, with 1 sigma";
//   spec.x = CategoryAxis("parameter (leg, name)", {"1a_x", "1a_y"});
//   spec.y = LinearAxis("change (mm)");
//   spec.series.push_back(BarSeries("change", {0.4, -0.7}, {0.1, 0.2}));
//   ChartRanges ranges = ComputeRanges(spec);  // y from -1 to 0.6: the negative bar shows
#pragma once

#include <string>
#include <vector>

namespace hexcal::charts {

// kPolylines: separate pieces (arrows, grid lines), each ended by a point
// with a NaN coordinate; one legend entry for them all.
enum class SeriesKind { kLine, kScatter, kBar, kPolylines };

struct ChartPoint {
  double x = 0;
  double y = 0;
};

struct AxisSpec {
  std::string label;  // with the unit: "residual (mm)"
  bool log = false;   // base 10; only positive values are drawn (see ComputeRanges)
  bool reversed = false;  // values grow downwards (or leftwards): image rows
  // The x axis of a bar chart: one label per bar (or group of bars), in order.
  std::vector<std::string> categories;
};

struct SeriesSpec {
  std::string name;  // legend entry
  SeriesKind kind = SeriesKind::kLine;
  std::vector<ChartPoint> points;  // line, scatter and polylines
  std::vector<double> values;      // bar: one per category
  std::vector<double> errors;      // bar: empty, or one symmetric error per value (0 or NaN: none)
  bool dashed = false;             // a limit or reference line, drawn grey and dashed
};

struct ChartSpec {
  std::string title;
  AxisSpec x;
  AxisSpec y;
  std::vector<SeriesSpec> series;
  int width = 760;   // pixels, when rendered to a file
  int height = 460;  // pixels

  // Categories on the x axis, or bar series (which may have no bars yet).
  bool IsBarChart() const;
  // Bar series only on a category x axis, each with one value (and error, if
  // any) per category; line and scatter series only on numeric x axes; a
  // positive size. `error` names the first problem.
  bool IsValid(std::string* error) const;
};

AxisSpec LinearAxis(std::string label);
AxisSpec LogAxis(std::string label);
AxisSpec CategoryAxis(std::string label, std::vector<std::string> categories);
SeriesSpec LineSeries(std::string name, std::vector<ChartPoint> points, bool dashed = false);
SeriesSpec ScatterSeries(std::string name, std::vector<ChartPoint> points);
// `pieces` drawn apart, one legend entry; `dashed` as for a line.
SeriesSpec PolylineSeries(std::string name, const std::vector<std::vector<ChartPoint>>& pieces, bool dashed = false);
SeriesSpec BarSeries(std::string name, std::vector<double> values, std::vector<double> errors = {});

// One axis as drawn: [min, max] and its labelled ticks.
struct AxisRange {
  double min = 0;
  double max = 1;
  bool log = false;
  // Linear: the multiples of one step of 1, 2 or 5 x 10^k from min to max
  // (min and max are ticks). Log: the powers of ten from min to max.
  // Bar-chart x axis: the category indices 0..n-1 (min -0.5, max n-0.5).
  std::vector<double> ticks;
  double step = 1;  // linear: the tick spacing; log: 10
};

struct ChartRanges {
  AxisRange x;
  AxisRange y;
};

// The axes of `spec`. The rule, for every series:
// - non-finite values (NaN, inf) are not data: they are skipped;
// - a linear axis holds every value, with a 3% margin that does not cross
//   zero, rounded out to its ticks; a bar chart's value axis also holds 0
//   (the bars' base) and value ± error of every bar;
// - a log axis holds every positive value (and the upper end value + error,
//   and the lower end when positive), rounded out to powers of ten;
//   non-positive values cannot be placed on it and are not drawn (a bar <= 0
//   has no height; an error bar reaching <= 0 is cut at the axis bottom);
// - no drawable data: [0, 1] linear, [1, 10] log.
ChartRanges ComputeRanges(const ChartSpec& spec);

// The linear axis for data in [lo, hi] with about `target_ticks` ticks.
AxisRange LinearRange(double lo, double hi, int target_ticks = 6);
// The log axis for positive data in [lo, hi].
AxisRange LogRange(double lo, double hi);

// A tick label: exact multiples print exactly ("0", "0.2", "-0.4", "1e-05"),
// with as many decimals as the step needs.
std::string TickLabel(double value, double step);

}  // namespace hexcal::charts

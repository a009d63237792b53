#include "charts/chart_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace hexcal::charts {
namespace {

constexpr double kMargin = 0.03;       // of the data span, each side of a linear axis
constexpr double kLogMargin = 1.02;    // factor, each side of a log axis
constexpr double kRelativeEps = 1e-9;  // rounding slack when comparing multiples of a step

// The data interval of one axis; on a log axis only positive values count.
class Extent {
 public:
  explicit Extent(bool log) : log_(log) {}
  bool Drawable(double v) const { return std::isfinite(v) && (!log_ || v > 0); }
  void Add(double v) {
    if (!Drawable(v)) return;
    lo_ = std::min(lo_, v);
    hi_ = std::max(hi_, v);
  }
  bool empty() const { return lo_ > hi_; }
  AxisRange Range() const {
    if (!empty()) return log_ ? LogRange(lo_, hi_) : LinearRange(lo_, hi_);
    AxisRange unit;  // nothing to draw: [0, 1] or [1, 10]
    unit.log = log_;
    unit.min = log_ ? 1 : 0;
    unit.max = log_ ? 10 : 1;
    unit.step = log_ ? 10 : 0.2;
    unit.ticks = log_ ? std::vector<double>{1, 10} : std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1};
    return unit;
  }

 private:
  bool log_;
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

// 1, 2 or 5 x 10^k, the nearest to `raw` on a log scale (Heckbert, "Nice
// numbers for graph labels", Graphics Gems, 1990).
double NiceStep(double raw) {
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double ratio = raw / power;
  return (ratio < 1.5 ? 1 : ratio < 3 ? 2 : ratio < 7 ? 5 : 10) * power;
}

AxisRange CategoryRange(size_t count) {
  AxisRange range;
  range.min = -0.5;
  range.max = static_cast<double>(std::max<size_t>(count, 1)) - 0.5;
  range.step = 1;
  for (size_t k = 0; k < count; ++k) range.ticks.push_back(static_cast<double>(k));
  return range;
}

// The bars' value axis: their base (0, linear only), values and error ends.
AxisRange BarValueRange(const ChartSpec& spec) {
  Extent extent(spec.y.log);
  if (!spec.y.log) extent.Add(0);
  for (const SeriesSpec& series : spec.series) {
    for (size_t k = 0; k < series.values.size(); ++k) {
      const double value = series.values[k];
      if (!extent.Drawable(value)) continue;  // no bar, so no error bar either
      extent.Add(value);
      const double error = k < series.errors.size() ? series.errors[k] : 0;
      if (!(std::isfinite(error) && error > 0)) continue;
      extent.Add(value + error);
      extent.Add(value - error);  // skipped on a log axis when <= 0: cut at the bottom
    }
  }
  return extent.Range();
}

}  // namespace

bool ChartSpec::IsBarChart() const {
  if (!x.categories.empty()) return true;
  for (const SeriesSpec& s : series) {
    if (s.kind == SeriesKind::kBar) return true;
  }
  return false;
}

bool ChartSpec::IsValid(std::string* error) const {
  const auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = "chart '" + title + "': " + message;
    return false;
  };
  if (width < 1 || height < 1) return fail("the size must be positive");
  if (IsBarChart() && x.log) return fail("a category axis cannot be logarithmic");
  for (const SeriesSpec& s : series) {
    const bool bar = s.kind == SeriesKind::kBar;
    if (bar != IsBarChart()) {
      return fail("series '" + s.name + (bar ? "' is bars on a numeric x axis" : "' is x-y data on a category axis"));
    }
    if (bar && s.values.size() != x.categories.size()) {
      return fail("series '" + s.name + "' has " + std::to_string(s.values.size()) + " values for " +
                  std::to_string(x.categories.size()) + " categories");
    }
    if (bar && !s.errors.empty() && s.errors.size() != s.values.size()) {
      return fail("series '" + s.name + "' has " + std::to_string(s.errors.size()) + " errors for " +
                  std::to_string(s.values.size()) + " values");
    }
  }
  return true;
}

AxisSpec LinearAxis(std::string label) {
  AxisSpec axis;
  axis.label = std::move(label);
  return axis;
}

AxisSpec LogAxis(std::string label) {
  AxisSpec axis = LinearAxis(std::move(label));
  axis.log = true;
  return axis;
}

AxisSpec CategoryAxis(std::string label, std::vector<std::string> categories) {
  AxisSpec axis = LinearAxis(std::move(label));
  axis.categories = std::move(categories);
  return axis;
}

SeriesSpec LineSeries(std::string name, std::vector<ChartPoint> points, bool dashed) {
  SeriesSpec series;
  series.name = std::move(name);
  series.points = std::move(points);
  series.dashed = dashed;
  return series;
}

SeriesSpec ScatterSeries(std::string name, std::vector<ChartPoint> points) {
  SeriesSpec series = LineSeries(std::move(name), std::move(points));
  series.kind = SeriesKind::kScatter;
  return series;
}

SeriesSpec PolylineSeries(std::string name, const std::vector<std::vector<ChartPoint>>& pieces, bool dashed) {
  SeriesSpec series = LineSeries(std::move(name), {}, dashed);
  series.kind = SeriesKind::kPolylines;
  for (const std::vector<ChartPoint>& piece : pieces) {
    series.points.insert(series.points.end(), piece.begin(), piece.end());
    series.points.push_back({std::nan(""), std::nan("")});
  }
  return series;
}

SeriesSpec BarSeries(std::string name, std::vector<double> values, std::vector<double> errors) {
  SeriesSpec series;
  series.name = std::move(name);
  series.kind = SeriesKind::kBar;
  series.values = std::move(values);
  series.errors = std::move(errors);
  return series;
}

ChartRanges ComputeRanges(const ChartSpec& spec) {
  ChartRanges ranges;
  if (spec.IsBarChart()) {
    ranges.x = CategoryRange(spec.x.categories.size());
    ranges.y = BarValueRange(spec);
    return ranges;
  }
  Extent x(spec.x.log), y(spec.y.log);
  for (const SeriesSpec& series : spec.series) {
    for (const ChartPoint& p : series.points) {
      if (!x.Drawable(p.x) || !y.Drawable(p.y)) continue;  // a point needs both coordinates
      x.Add(p.x);
      y.Add(p.y);
    }
  }
  ranges.x = x.Range();
  ranges.y = y.Range();
  return ranges;
}

AxisRange LinearRange(double lo, double hi, int target_ticks) {
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) {  // one value: an interval around it
    const double half = lo == 0 ? 0.5 : std::abs(lo) * 0.1;
    lo -= half;
    hi += half;
  }
  const double margin = kMargin * (hi - lo);
  // The margin keeps points off the frame, but an axis of positive data (or
  // bars from 0) does not dip below zero for it.
  const double padded_lo = lo >= 0 ? std::max(0.0, lo - margin) : lo - margin;
  const double padded_hi = hi <= 0 ? std::min(0.0, hi + margin) : hi + margin;
  const double step = NiceStep((padded_hi - padded_lo) / std::max(1, target_ticks - 1));
  AxisRange range;
  if (!std::isfinite(step) || step <= 0) {  // a span beyond double range: no rounding
    range.min = lo;
    range.max = hi;
    range.ticks = {lo, hi};
    range.step = hi - lo;
    return range;
  }
  double first = std::floor(padded_lo / step + kRelativeEps);
  double last = std::ceil(padded_hi / step - kRelativeEps);
  while (first * step > lo) first -= 1;  // rounding must never cut data off
  while (last * step < hi) last += 1;
  range.min = first * step;
  range.max = last * step;
  range.step = step;
  for (double k = first; k <= last; k += 1) range.ticks.push_back(k * step);
  return range;
}

AxisRange LogRange(double lo, double hi) {
  if (hi < lo) std::swap(lo, hi);
  int first = static_cast<int>(std::floor(std::log10(lo / kLogMargin)));
  int last = static_cast<int>(std::ceil(std::log10(hi * kLogMargin)));
  if (last <= first) last = first + 1;
  while (std::pow(10.0, first) > lo) --first;  // pow and log10 round: keep the data inside
  while (std::pow(10.0, last) < hi) ++last;
  AxisRange range;
  range.log = true;
  range.min = std::pow(10.0, first);
  range.max = std::pow(10.0, last);
  range.step = 10;
  for (int e = first; e <= last; ++e) range.ticks.push_back(std::pow(10.0, e));
  return range;
}

std::string TickLabel(double value, double step) {
  if (std::abs(value) < std::abs(step) * 1e-6) return "0";  // not "-2.8e-17"
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - kRelativeEps));
  char text[40];
  if (decimals > 6 || std::abs(value) >= 1e6) {
    std::snprintf(text, sizeof text, "%.6g", value);
  } else {
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
  }
  return text;
}

}  // namespace hexcal::charts

// For the chart tests: does an axis range hold every value a spec draws?
// Written apart from ComputeRanges, from the rule in chart_spec.h, so that
// the figure tests check the ranges rather than repeat them.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "charts/chart_spec.h"

namespace hexcal::charts {

inline bool OnAxis(double v, const AxisSpec& axis) { return std::isfinite(v) && (!axis.log || v > 0); }

inline bool Inside(double v, const AxisRange& range) { return v >= range.min && v <= range.max; }

// Every point of every line and scatter series; every bar (index on x,
// value and its base 0 on a linear y), and both ends of its error bar (the
// lower end only where the axis can hold it).
inline ::testing::AssertionResult RangesContainData(const ChartSpec& spec, const ChartRanges& ranges) {
  std::ostringstream outside;
  const auto check = [&](const std::string& series, const char* what, double v, const AxisRange& range) {
    if (!Inside(v, range))
      outside << series << ": " << what << " " << v << " not in [" << range.min << ", " << range.max << "]; ";
  };
  for (const SeriesSpec& s : spec.series) {
    for (const ChartPoint& p : s.points) {
      if (!OnAxis(p.x, spec.x) || !OnAxis(p.y, spec.y)) continue;
      check(s.name, "x", p.x, ranges.x);
      check(s.name, "y", p.y, ranges.y);
    }
    for (size_t k = 0; k < s.values.size(); ++k) {
      check(s.name, "category", static_cast<double>(k), ranges.x);
      if (!spec.y.log) check(s.name, "bar base", 0, ranges.y);
      if (!OnAxis(s.values[k], spec.y)) continue;
      check(s.name, "bar", s.values[k], ranges.y);
      const double error = k < s.errors.size() ? s.errors[k] : 0;
      if (!(std::isfinite(error) && error > 0)) continue;
      check(s.name, "error bar top", s.values[k] + error, ranges.y);
      if (OnAxis(s.values[k] - error, spec.y)) check(s.name, "error bar bottom", s.values[k] - error, ranges.y);
    }
  }
  if (outside.str().empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "chart '" << spec.title << "': " << outside.str();
}

// The same for the ranges the chart is drawn with.
inline ::testing::AssertionResult AxesContainData(const ChartSpec& spec) {
  return RangesContainData(spec, ComputeRanges(spec));
}

}  // namespace hexcal::charts

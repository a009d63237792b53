// The axis rule of ComputeRanges: every drawable value inside, negatives and
// error bars included; ticks at round values; log axes of positive data.
#include "charts/chart_spec.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "charts/chart_test_support.h"
#include "tests/test_support.h"

namespace hexcal::charts {
namespace {

using ::hexcal::testing::Uniform;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every tick is an integer multiple of a step of 1, 2 or 5 x 10^k, from min to max.
void ExpectRoundTicks(const AxisRange& range) {
  ASSERT_FALSE(range.ticks.empty());
  EXPECT_EQ(range.ticks.front(), range.min);
  EXPECT_EQ(range.ticks.back(), range.max);
  const double mantissa = range.step / std::pow(10.0, std::floor(std::log10(range.step)));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9)
      << "step " << range.step;
  for (double tick : range.ticks) EXPECT_NEAR(tick / range.step, std::round(tick / range.step), 1e-9);
}

TEST(LinearRange, TicksAreRoundAndHoldTheData) {
  const AxisRange range = LinearRange(0.13, 0.91);
  EXPECT_LE(range.min, 0.13);
  EXPECT_GE(range.max, 0.91);
  ExpectRoundTicks(range);
  EXPECT_THAT(LinearRange(0, 1).ticks.size(), ::testing::AllOf(::testing::Ge(4u), ::testing::Le(11u)));
}

TEST(LinearRange, NegativeDataIsInside) {
  const AxisRange range = LinearRange(-0.73, 0.41);
  EXPECT_LE(range.min, -0.73);
  EXPECT_GE(range.max, 0.41);
  EXPECT_LT(range.min, -0.73);  // a margin keeps the lowest point off the frame
  ExpectRoundTicks(range);
  const AxisRange all_negative = LinearRange(-250, -240);
  EXPECT_LE(all_negative.min, -250);
  EXPECT_GE(all_negative.max, -240);
  EXPECT_LE(all_negative.max, 0);  // the margin does not reach over zero
}

TEST(LinearRange, PositiveDataDoesNotDipBelowZero) {
  EXPECT_EQ(LinearRange(0, 3).min, 0);
  EXPECT_GE(LinearRange(0.05, 3).min, 0);
}

TEST(LinearRange, OneValueGetsAnIntervalAroundIt) {
  for (double v : {5.0, 0.0, -2.0}) {
    const AxisRange range = LinearRange(v, v);
    EXPECT_LT(range.min, v) << v;
    EXPECT_GT(range.max, v) << v;
  }
}

TEST(LogRange, SpansEveryDecadeOfTheData) {
  const AxisRange range = LogRange(0.0024, 0.25);
  EXPECT_TRUE(range.log);
  EXPECT_DOUBLE_EQ(range.min, 0.001);
  EXPECT_DOUBLE_EQ(range.max, 1);
  EXPECT_THAT(range.ticks, ElementsAre(0.001, 0.01, 0.1, 1));
  // A value at a power of ten stays off the frame, and inside however pow rounds.
  const AxisRange exact = LogRange(0.001, 1000);
  EXPECT_LT(exact.min, 0.001);
  EXPECT_GT(exact.max, 1000);
}

TEST(ComputeRanges, BarChartWithNegativeBarsAndErrorsHoldsThemAll) {
  ChartSpec spec;
  spec.x.categories = {"1a_x", "1a_y", "1l"};
  spec.series.push_back(BarSeries("change", {0.4, -0.7, -0.05}, {0.1, 0.2, kNaN}));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_LE(ranges.y.min, -0.9);  // -0.7 - 0.2
  EXPECT_GE(ranges.y.max, 0.5);
  EXPECT_DOUBLE_EQ(ranges.x.min, -0.5);
  EXPECT_DOUBLE_EQ(ranges.x.max, 2.5);
  EXPECT_THAT(ranges.x.ticks, ElementsAre(0, 1, 2));
  EXPECT_TRUE(RangesContainData(spec, ranges));
}

// The example at the top of chart_spec.h.
TEST(ComputeRanges, HeaderExample) {
  ChartSpec spec;
  spec.x = CategoryAxis("parameter (leg, name)", {"1a_x", "1a_y"});
  spec.series.push_back(BarSeries("change", {0.4, -0.7}, {0.1, 0.2}));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_DOUBLE_EQ(ranges.y.min, -1);
  EXPECT_DOUBLE_EQ(ranges.y.max, 0.6);
}

TEST(ComputeRanges, BarsStandOnZero) {
  ChartSpec spec;
  spec.x.categories = {"a", "b"};
  spec.series.push_back(BarSeries("v", {240, 250}));
  EXPECT_EQ(ComputeRanges(spec).y.min, 0);
}

TEST(ComputeRanges, LogAxisHoldsThePositiveValuesOnly) {
  ChartSpec spec;
  spec.y.log = true;
  spec.series.push_back(LineSeries("o", {{0, -1}, {1, 0}, {2, 0.5}, {3, 20}, {4, kNaN}}));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_DOUBLE_EQ(ranges.y.min, 0.1);
  EXPECT_DOUBLE_EQ(ranges.y.max, 100);
  // The x axis holds the points that are drawn: x = 2 and 3.
  EXPECT_LE(ranges.x.min, 2);
  EXPECT_GE(ranges.x.max, 3);
  EXPECT_TRUE(RangesContainData(spec, ranges));
}

TEST(ComputeRanges, LogBarErrorReachingBelowZeroIsCutAtTheBottom) {
  ChartSpec spec;
  spec.y.log = true;
  spec.x.categories = {"before", "plan"};
  spec.series.push_back(BarSeries("mean ± std", {0.25, 0.0024}, {0.15, 0.005}));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_DOUBLE_EQ(ranges.y.min, 0.001);
  EXPECT_DOUBLE_EQ(ranges.y.max, 1);
}

TEST(ComputeRanges, NoDataGivesAUnitAxis) {
  ChartSpec spec;
  spec.series.push_back(LineSeries("empty", {{kNaN, 1}}));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_EQ(ranges.x.min, 0);
  EXPECT_EQ(ranges.x.max, 1);
  spec.y.log = true;
  EXPECT_EQ(ComputeRanges(spec).y.min, 1);
  EXPECT_EQ(ComputeRanges(spec).y.max, 10);
}

TEST(ComputeRanges, RandomDataIsAlwaysInside) {
  for (int trial = 0; trial < 200; ++trial) {
    const double scale = std::pow(10.0, Uniform(-6, 6)), offset = Uniform(-3, 3) * scale;
    ChartSpec lines, bars;
    bars.x.categories = {"a", "b", "c", "d"};
    for (int s = 0; s < 3; ++s) {
      std::vector<ChartPoint> points;
      std::vector<double> values, errors;
      for (int k = 0; k < 4; ++k) {
        points.push_back({Uniform(-1, 1) * scale, offset + Uniform(-1, 1) * scale});
        values.push_back(offset + Uniform(-1, 1) * scale);
        errors.push_back(Uniform(0, 0.5) * scale);
      }
      lines.series.push_back(LineSeries("s", points));
      bars.series.push_back(BarSeries("s", values, errors));
    }
    ASSERT_TRUE(RangesContainData(lines, ComputeRanges(lines))) << "trial " << trial;
    ASSERT_TRUE(RangesContainData(bars, ComputeRanges(bars))) << "trial " << trial;
    ExpectRoundTicks(ComputeRanges(lines).y);
  }
}

// The check the figure tests rely on can fail: a range that cuts off a
// negative value, or an error bar, is caught.
TEST(RangesContainData, CatchesDataOutsideTheAxes) {
  ChartSpec spec;
  spec.x.categories = {"a", "b"};
  spec.series.push_back(BarSeries("change", {0.5, -0.5}, {0.1, 0.1}));
  ChartRanges cut = ComputeRanges(spec);
  cut.y.min = 0;  // what the hand-written SVG chart did: negative bars gone
  const ::testing::AssertionResult result = RangesContainData(spec, cut);
  EXPECT_FALSE(result);
  EXPECT_THAT(result.message(), HasSubstr("-0.5"));
  cut = ComputeRanges(spec);
  cut.y.max = 0.55;  // the bar, but not its error bar
  EXPECT_FALSE(RangesContainData(spec, cut));
}

TEST(ComputeRanges, PolylinesHoldEveryPieceAndTheirBreaksAreNotData) {
  ChartSpec spec;
  spec.series = {PolylineSeries("grid", {{{0, 0}, {640, 0}}, {{0, 480}, {640, 480}}})};
  ASSERT_EQ(spec.series[0].points.size(), 6u);  // two pieces, each ended by a NaN break
  EXPECT_TRUE(std::isnan(spec.series[0].points[2].x));
  EXPECT_TRUE(spec.IsValid(nullptr));
  const ChartRanges ranges = ComputeRanges(spec);
  EXPECT_LE(ranges.x.min, 0);
  EXPECT_GE(ranges.x.max, 640);
  EXPECT_LE(ranges.y.min, 0);
  EXPECT_GE(ranges.y.max, 480);
  EXPECT_LT(ranges.y.max, 600);
}

TEST(TickLabel, PrintsExactMultiples) {
  EXPECT_EQ(TickLabel(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(TickLabel(-2.7755575615628914e-17, 0.2), "0");
  EXPECT_EQ(TickLabel(-0.4, 0.2), "-0.4");
  EXPECT_EQ(TickLabel(250, 50), "250");
  EXPECT_EQ(TickLabel(0.005, 0.005), "0.005");
  EXPECT_EQ(TickLabel(0.0015, 0.0005), "0.0015");
  EXPECT_EQ(TickLabel(3e-8, 1e-8), "3e-08");
}

TEST(ChartSpec, IsValidNamesTheProblem) {
  ChartSpec spec;
  spec.title = "t";
  spec.x.categories = {"a", "b"};
  spec.series.push_back(BarSeries("v", {1}));
  std::string error;
  EXPECT_FALSE(spec.IsValid(&error));
  EXPECT_THAT(error, HasSubstr("'v' has 1 values for 2 categories"));
  spec.series[0] = BarSeries("v", {1, 2}, {0.1});
  EXPECT_FALSE(spec.IsValid(&error));
  EXPECT_THAT(error, HasSubstr("1 errors for 2 values"));
  spec.series[0] = BarSeries("v", {1, 2});
  spec.series.push_back(LineSeries("line", {{0, 1}}));
  EXPECT_FALSE(spec.IsValid(&error));
  EXPECT_THAT(error, HasSubstr("x-y data on a category axis"));
  spec.series.pop_back();
  EXPECT_TRUE(spec.IsValid(&error));
}

}  // namespace
}  // namespace hexcal::charts

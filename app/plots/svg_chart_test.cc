// The SVG chart writer: one bar or polyline per datum, escaped labels, ticks
// at round values, log axes that hold every value.
#include "app/plots/svg_chart.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <regex>

#include "app/plots/simulation_figures.h"

namespace hexcal::plots {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

int Count(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// Every y coordinate of the elements, which must lie inside the image.
void ExpectInside(const std::string& svg, int height) {
  const std::regex y_attribute(" (?:y|y1|y2|cy)=\"(-?[0-9.]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), y_attribute); it != std::sregex_iterator(); ++it) {
    const double y = std::stod((*it)[1]);
    EXPECT_GE(y, 0);
    EXPECT_LE(y, height);
  }
}

TEST(SvgChart, LinearTicksAreRoundNumbers) {
  EXPECT_THAT(LinearTicks(0, 1), ElementsAre(0, 0.2, 0.4, 0.6000000000000001, 0.8, 1));
  EXPECT_THAT(LinearTicks(8, 41, 10), ElementsAre(5, 10, 15, 20, 25, 30, 35, 40, 45));
}

TEST(SvgChart, BarChartHasOneBarPerValueAndEscapesText) {
  ChartOptions options;
  options.title = "a < b & c";
  options.y_label = "error (cm)";
  const std::string svg = BarChartSvg(options, {{"before", 0.25, 0.15}, {"random", 0.04, 0.038}, {"plan", 0.002, 0}});
  EXPECT_THAT(svg, HasSubstr("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"760\" height=\"460\""));
  EXPECT_THAT(svg, HasSubstr("a &lt; b &amp; c"));
  EXPECT_EQ(Count(svg, "<rect"), 1 + 3);  // background and three bars
  EXPECT_THAT(svg, HasSubstr(">random</text>"));
  EXPECT_THAT(svg, HasSubstr(">0.04</text>"));
  EXPECT_THAT(svg, HasSubstr("</svg>"));
  ExpectInside(svg, options.height);
}

TEST(SvgChart, LogAxisSpansEveryDecadeOfTheData) {
  ChartOptions options;
  options.log_y = true;
  const std::string svg = BarChartSvg(options, {{"before", 0.25, 0.15}, {"plan", 0.0024, 0.0013}});
  for (const char* tick : {">0.001</text>", ">0.01</text>", ">0.1</text>", ">1</text>"}) {
    EXPECT_THAT(svg, HasSubstr(tick));
  }
  ExpectInside(svg, options.height);
}

TEST(SvgChart, LineChartDrawsEachSeriesWithALegend) {
  ChartOptions options;
  options.log_y = true;
  options.x_label = "number of poses";
  const std::string svg =
      LineChartSvg(options, {{"random", {8, 9, 10}, {0.3, 0.1, 0.05}}, {"boundary", {8, 9}, {0.01, 0.004}}});
  EXPECT_EQ(Count(svg, "<polyline"), 2);
  EXPECT_EQ(Count(svg, "<circle"), 5);
  EXPECT_THAT(svg, HasSubstr(">boundary</text>"));
  EXPECT_THAT(svg, HasSubstr(">number of poses</text>"));
  ExpectInside(svg, options.height);
}

TEST(SimulationFigures, Fig14HasBeforeAndEverySet) {
  SimulationResult result;
  result.before = {42, 0.25, 0.14, 0, 0};
  SetError random, boundary;
  random.name = "random";
  random.poses = 18;
  random.mean = 0.04;
  boundary.name = "boundary";
  boundary.poses = 44;
  boundary.mean = 0.003;
  result.sets = {random, boundary};
  const std::string svg = Fig14Svg(result, "cm");
  EXPECT_THAT(svg, HasSubstr(">before</text>"));
  EXPECT_THAT(svg, HasSubstr(">random (18)</text>"));
  EXPECT_THAT(svg, HasSubstr(">boundary (44)</text>"));
  EXPECT_THAT(svg, HasSubstr("|P_est - P_true| (cm)"));
}

}  // namespace
}  // namespace hexcal::plots

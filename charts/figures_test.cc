// Every figure definition: a valid spec whose axes hold all its data,
// negative values and error bars included, with the labels and series the
// figure is read by.
#include "charts/figures.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "charts/chart_test_support.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/simulation.h"

namespace hexcal::charts {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Robot Inria() {
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  EXPECT_TRUE(robot.ok()) << robot.status().message();
  return *robot;
}

void ExpectValid(const ChartSpec& spec) {
  std::string error;
  EXPECT_TRUE(spec.IsValid(&error)) << error;
  EXPECT_TRUE(AxesContainData(spec));
}

std::vector<std::string> Names(const ChartSpec& spec) {
  std::vector<std::string> names;
  for (const SeriesSpec& s : spec.series) names.push_back(s.name);
  return names;
}

double MinY(const ChartSpec& spec) {
  double lo = std::numeric_limits<double>::infinity();
  for (const SeriesSpec& s : spec.series)
    for (const ChartPoint& p : s.points) lo = std::min(lo, p.y);
  return lo;
}

SetError Set(const std::string& name, int poses, double mean, double std) {
  SetError set;
  set.name = name;
  set.poses = poses;
  set.mean = mean;
  set.std = std;
  return set;
}

TEST(Fig14Chart, BarsOfBeforeAndEverySetWithTheirErrors) {
  SimulationResult result;
  result.before.mean = 0.25;
  result.before.std = 0.14;
  // std above the mean: the error bar reaches below zero, cut at the log axis bottom.
  result.sets = {Set("random", 18, 0.04, 0.05), Set("boundary", 44, 0.003, 0.001)};
  const ChartSpec spec = Fig14Chart(result, "cm");
  ExpectValid(spec);
  EXPECT_THAT(spec.x.categories, ElementsAre("before", "random (18)", "boundary (44)"));
  EXPECT_THAT(spec.y.label, HasSubstr("|P_est - P_true| (cm)"));
  EXPECT_TRUE(spec.y.log);
  EXPECT_THAT(spec.series[0].errors, ElementsAre(0.14, 0.05, 0.001));
  EXPECT_LE(ComputeRanges(spec).y.min, 0.002);
}

TEST(SubsetHistogramChart, OutlineCountsEveryValueAndMarksTheSelected) {
  // 4 bins over [0, 4]: 0.5 in the first, 1.5 in the second, 3.9 and 4 (the top edge) in the last; NaN left out.
  const ChartSpec spec = SubsetHistogramChart("Fig. 19", "position (cm)", {0.5, 1.5, 3.9, 4.0, NAN}, 0.0, 4);
  ExpectValid(spec);
  ASSERT_EQ(spec.series.size(), 2u);
  const std::vector<ChartPoint>& outline = spec.series[0].points;
  ASSERT_EQ(outline.size(), 10u);  // (0, 0), two corners per bin, (4, 0)
  std::vector<double> heights;
  for (size_t k = 1; k + 1 < outline.size(); k += 2) heights.push_back(outline[k].y);
  EXPECT_THAT(heights, ElementsAre(1, 1, 0, 2));
  EXPECT_DOUBLE_EQ(outline[2].x, 1.0);
  EXPECT_EQ(spec.series[0].name, "4 random subsets");
  EXPECT_TRUE(spec.series[1].dashed);
  EXPECT_DOUBLE_EQ(spec.series[1].points[0].x, 0.0);
  EXPECT_DOUBLE_EQ(spec.series[1].points[1].y, 2.0);  // as tall as the tallest bin
}

TEST(StudyMetricChart, Fig18ForAnIndexFig19ForAHeldOutError) {
  const ChartSpec index = StudyMetricChart(SubsetMetric::kO1, {1, 2, 3}, 2.5, 13, "cm");
  EXPECT_EQ(index.title, "Fig. 18: O1 (cm), N = 13");  // O1 carries its unit (issue 39)
  EXPECT_EQ(index.series[0].name, "3 random subsets");
  EXPECT_EQ(index.x.label, "O1 (cm)");
  const ChartSpec error = StudyMetricChart(SubsetMetric::kHeldOutPosition, {0.1, 0.2}, NAN, 13, "cm");
  EXPECT_EQ(error.title, "Fig. 19: held-out position RMS (cm), N = 13");
  EXPECT_EQ(error.x.label, "held-out position RMS (cm)");
  EXPECT_EQ(error.series.size(), 1u);  // no selected value: no dashed line
}

TEST(Fig15Chart, OneLinePerSetAgainstThePoseCount) {
  SweepResult sweep;
  sweep.points = {{8, {Set("random", 8, 0.3, 0.2), Set("plan", 8, 0.01, 0.004)}},
                  {9, {Set("random", 9, 0.1, 0.05), Set("plan", 9, 0.008, 0.003)}},
                  {10, {Set("random", 10, 0.05, 0.02)}}};
  for (bool std_dev : {false, true}) {
    const ChartSpec spec = Fig15Chart(sweep, "mm", std_dev);
    ExpectValid(spec);
    EXPECT_THAT(Names(spec), ElementsAre("random", "plan"));
    EXPECT_EQ(spec.series[0].points.size(), 3u);
    EXPECT_EQ(spec.series[1].points.size(), 2u);
    EXPECT_EQ(spec.series[0].points[1].y, std_dev ? 0.05 : 0.1);
    EXPECT_THAT(spec.title, HasSubstr(std_dev ? "standard deviation" : "mean"));
  }
}

TEST(LegReadingsChart, EveryLegOfEveryPoseAndTheStrokesIncludingReadingsBelowZero) {
  const Robot robot = Inria();
  // At z = 50 cm the legs are shorter than at the stroke's zero: negative readings.
  const std::vector<Vector6d> plan = {(Vector6d() << 0, 0, 53, 0, 0, 0).finished(),
                                      (Vector6d() << 2, -1, 50, 5, 0, 10).finished(),
                                      (Vector6d() << -3, 2, 55, 0, -8, -5).finished()};
  const ChartSpec spec = LegReadingsChart(robot, plan);
  ExpectValid(spec);
  EXPECT_THAT(Names(spec), ElementsAre("L1", "L2", "L3", "L4", "L5", "L6", "stroke min", "stroke max"));
  EXPECT_TRUE(spec.series[6].dashed);
  EXPECT_EQ(spec.series[0].kind, SeriesKind::kScatter);
  EXPECT_EQ(spec.series[0].points.size(), 3u);
  EXPECT_LT(MinY(spec), 0);
  EXPECT_LT(ComputeRanges(spec).y.min, MinY(spec));
  EXPECT_DOUBLE_EQ(spec.series[1].points[2].y, InverseKinematics(robot, robot.PoseFromVector(plan[2]))[1]);
}

TEST(LegReadingsChart, LegsWithDifferentStrokesEachGetTheirLine) {
  Robot robot = Inria();
  robot.legs[2].stroke_max = 4;
  const ChartSpec spec = LegReadingsChart(robot, {(Vector6d() << 0, 0, 53, 0, 0, 0).finished()});
  ExpectValid(spec);
  EXPECT_THAT(Names(spec), ::testing::Contains("stroke max (legs 1,2,4,5,6)"));
  EXPECT_THAT(Names(spec), ::testing::Contains("stroke max (legs 3)"));
}

TEST(ObservabilityChart, FourIndicesPerIterationOnALogAxis) {
  PlanIteration first, second;
  first.indices = {1.5, 0.002, 1e-5, 0.3};
  second.iteration = 1;
  second.indices = {2.5, 0.004, 0, 0.4};  // an index of 0 cannot be placed on the log axis
  const ChartSpec spec = ObservabilityChart({first, second});
  ExpectValid(spec);
  EXPECT_TRUE(spec.y.log);
  EXPECT_THAT(Names(spec), ElementsAre("O1", "O2", "O3", "O4"));
  EXPECT_EQ(spec.series[2].points[1].y, 0);
  EXPECT_LE(ComputeRanges(spec).y.min, 1e-5);
  EXPECT_THAT(IndexValues(second.indices), ElementsAre(2.5, 0.004, 0, 0.4));
  ExpectValid(ObservabilityChart({}));  // the live chart starts empty
}

TEST(MeasurementRmsChart, OneValuePerImage) {
  const ChartSpec spec = MeasurementRmsChart({0.12, 0.31, kNaN, 0.08});
  ExpectValid(spec);
  ASSERT_EQ(spec.series.size(), 1u);
  EXPECT_EQ(spec.series[0].points.size(), 4u);
  EXPECT_EQ(spec.series[0].points[3].x, 4);
  EXPECT_EQ(spec.y.label, "reprojection RMS (px)");
}

TEST(CalibrationResidualsChart, SignedResidualsOfBothRobots) {
  const Robot nominal = Inria();
  const Robot calibrated = PerturbedRobot(nominal, 0.05, 7);
  std::vector<Measurement> rows(3);
  const double offsets[3] = {0.2, -0.3, 0.05};
  for (int j = 0; j < 3; ++j) {
    rows[j].pose << j, -j, 52 + j, 2 * j, 0, -3 * j;
    rows[j].legs = (InverseKinematics(nominal, nominal.PoseFromVector(rows[j].pose)).array() + offsets[j]).matrix();
  }
  const ChartSpec spec = CalibrationResidualsChart(nominal, calibrated, rows);
  ExpectValid(spec);
  EXPECT_THAT(Names(spec), ElementsAre("nominal robot", "calibrated robot"));
  ASSERT_EQ(spec.series[0].points.size(), 18u);
  EXPECT_NEAR(spec.series[0].points[0].y, -0.2, 1e-9);  // IK - reading
  EXPECT_NEAR(spec.series[0].points[6].y, 0.3, 1e-9);
  EXPECT_NEAR(spec.series[0].points[6].x, 2 - 2.5 / 6, 1e-12);  // leg 1 of pose 2
  EXPECT_LE(ComputeRanges(spec).y.min, -0.2);
  EXPECT_THAT(spec.y.label, HasSubstr("(cm)"));
}

// The figure the hand-written SVG chart got wrong: negative changes must show.
TEST(ParameterChangeChart, NegativeChangesAndTheirSigmasAreOnTheAxis) {
  const std::vector<ParameterChange> changes = {
      {1, "a_x", 0.12, 0.03}, {1, "a_y", -0.4, 0.05}, {1, "l", -0.02, kNaN}, {2, "b_z", 0.3, 0}};
  const ChartSpec spec = ParameterChangeChart(changes, "mm");
  ExpectValid(spec);
  EXPECT_THAT(spec.x.categories, ElementsAre("a_x", "a_y", "l", "b_z"));
  EXPECT_THAT(Names(spec), ElementsAre("leg 1", "leg 2"));
  EXPECT_THAT(spec.series[0].values, ElementsAre(0.12, -0.4, -0.02, ::testing::IsNan()));
  EXPECT_THAT(spec.series[1].values, ElementsAre(::testing::IsNan(), ::testing::IsNan(), ::testing::IsNan(), 0.3));
  EXPECT_EQ(spec.series[0].errors[1], 0.05);
  EXPECT_LE(ComputeRanges(spec).y.min, -0.45);
  EXPECT_GE(ComputeRanges(spec).y.max, 0.3);
  EXPECT_EQ(spec.y.label, "change (mm)");
}

TEST(ValidationSummaryChart, BeforeAndAfterPerQuantityOnALogAxis) {
  const ChartSpec spec = ValidationSummaryChart({0.8, 0.004, 0.5, 0.002}, "mm");
  ExpectValid(spec);
  EXPECT_TRUE(spec.y.log);
  EXPECT_THAT(spec.x.categories, ElementsAre("position (mm)", "orientation (deg)"));
  EXPECT_THAT(spec.series[0].values, ElementsAre(0.8, 0.5));
  EXPECT_THAT(spec.series[1].values, ElementsAre(0.004, 0.002));
}

TEST(ValidationPerImageChart, OneGroupPerImage) {
  const std::vector<ImageValidation> images = {{"3", {0.5, 0.01, 0.2, 0.004}}, {"7", {0.7, 0, 0.3, kNaN}}};
  const ChartSpec position = ValidationPerImageChart(images, ValidationQuantity::kPosition, "mm");
  const ChartSpec orientation = ValidationPerImageChart(images, ValidationQuantity::kOrientation, "mm");
  ExpectValid(position);
  ExpectValid(orientation);
  EXPECT_THAT(position.x.categories, ElementsAre("3", "7"));
  EXPECT_THAT(position.series[1].values, ElementsAre(0.01, 0));
  EXPECT_THAT(orientation.series[0].values, ElementsAre(0.2, 0.3));
  EXPECT_EQ(position.y.label, "position error (mm)");
  EXPECT_EQ(position.title, "Held-out position error per image");
  EXPECT_EQ(position.x.label, "image number");
  // A points session's rows are poses.
  const ChartSpec poses = ValidationPerImageChart(images, ValidationQuantity::kOrientation, "mm", "pose");
  EXPECT_EQ(poses.title, "Held-out orientation error per pose");
  EXPECT_EQ(poses.x.label, "pose number");
  const ChartSpec empty = ValidationPerImageChart({}, ValidationQuantity::kPosition, "");  // no results yet
  ExpectValid(empty);
  EXPECT_EQ(empty.y.label, "position error");
}

}  // namespace
}  // namespace hexcal::charts

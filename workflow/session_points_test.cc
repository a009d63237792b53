// The calibration from points on the demo's tracker sessions of both robots,
// against the two-stage calibration of the same session and the hidden truth
// (docs/calibration.md, "Calibration from points"); what results/ and the
// report get; the other instrument's joint fit asked for by name is refused.
#include "workflow/session_points.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/point_file.h"
#include "tests/test_support.h"
#include "report/calibration_verdict.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::TempDir;
using ::testing::HasSubstr;

DemoResult Demo(const TempDir& dir, const std::string& robot, bool joint, Instrument instrument = Instrument::kPoints) {
  DemoRequest request = FitComparisonDemo(robot, dir.File(robot + (joint ? "-joint" : "-two-stage")));
  request.from_pixels = joint;
  request.instrument = instrument;
  return RunDemoInTest(request);
}

class FromPoints : public ::testing::TestWithParam<std::string> {};

TEST_P(FromPoints, IsAsAccurateAsTwoStageWithHonestSigmas) {
  TempDir dir;
  const DemoResult poses = Demo(dir, GetParam(), false);
  const DemoResult joint = Demo(dir, GetParam(), true);
  EXPECT_FALSE(poses.calibration.from_points.has_value());
  ASSERT_TRUE(joint.calibration.from_points.has_value());
  const PointFitSummary& fit = *joint.calibration.from_points;
  EXPECT_TRUE(fit.reflectors_estimated && fit.reflectors_from_file);
  EXPECT_EQ(fit.rank, fit.unknowns);
  EXPECT_EQ(fit.unknowns, 42 + 3 * 4 - 6);
  EXPECT_NEAR(fit.reflector_scale, 1, 4 * fit.reflector_scale_sigma + 1e-12);
  EXPECT_GE(joint.within_3sigma, 0.95);
  // One seed: within 25 % (docs/calibration.md has the mean over seeds).
  EXPECT_LE(joint.error_mean, 1.25 * poses.error_mean);
  // The reflectors' finding (the quick plan's parameter σ decide the level).
  EXPECT_THAT(joint.verdict.ToText(), HasSubstr("good       reflectors (scale)"));
  std::printf("%s, tracker: mean parameter error %.5g two-stage (%.3f within 3 sigma), %.5g from points (%.3f)\n",
              GetParam().c_str(), poses.error_mean, poses.within_3sigma, joint.error_mean, joint.within_3sigma);
  // results/: the fitted reflectors, a reflector file the session can take, and every point's residual.
  const std::filesystem::path results = std::filesystem::path(joint.session) / "results";
  StatusOr<std::vector<NamedPoint>> reflectors = LoadReflectorFile((results / "reflectors.csv").string());
  ASSERT_TRUE(reflectors.ok()) << reflectors.status().message();
  EXPECT_EQ(reflectors->size(), 4u);
  EXPECT_TRUE(std::filesystem::exists(results / "point_residuals.csv"));
  // report.json round trip.
  StatusOr<CalibrationReport> loaded = LoadCalibrationReport(CalibrationReportPath(joint.session));
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  ASSERT_TRUE(loaded->from_points.has_value());
  EXPECT_EQ(ToJson(*loaded->from_points), ToJson(fit));
}

INSTANTIATE_TEST_SUITE_P(BothRobots, FromPoints, ::testing::Values("inria-left-hand", "deltalab-table"));

TEST(FromPoints, KeepsTheReflectorsWhenAskedAndRefusesTheOtherInstrumentsFit) {
  TempDir dir;
  const DemoResult demo = Demo(dir, "inria-left-hand", false);
  CalibrateSessionRequest request{demo.session};
  request.from_points.estimate_reflectors = false;
  StatusOr<CalibrationReport> kept = CalibrateSession(request);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  ASSERT_TRUE(kept->from_points.has_value());
  EXPECT_FALSE(kept->from_points->reflectors_estimated);
  EXPECT_EQ(kept->from_points->unknowns, 42);

  CalibrateSessionRequest pixels{demo.session};
  pixels.from_pixels.fall_back = false;  // --from-pixels
  StatusOr<CalibrationReport> refused = CalibrateSession(pixels);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().kind(), StatusKind::kBadInput);
  EXPECT_THAT(refused.status().message(), HasSubstr("a points session has no pixels; --from-points"));
}

}  // namespace
}  // namespace hexcal::workflow

// The demo and the session calibration as the front ends call them: typed
// requests and results, stages and progress through JobHooks, cancel.
#include "workflow/demo.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/atomic_file.h"
#include "report/session_report.h"
#include "session/corner_residuals_file.h"
#include "tests/test_support.h"
#include "workflow/session_calibrate.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using hexcal::testing::ReadTextFile;
using hexcal::testing::SourceDir;
using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;

// One demo for the tests below: 10 planned poses, 3 held out, seed 3.
class DemoSession : public DemoSessionSuite<DemoSession> {
 public:
  static DemoRequest Request() { return SmallDemo(/*poses=*/10, /*holdout=*/3, /*seed=*/3); }
};

TEST_F(DemoSession, CalibratesCloserToTheTruth) {
  EXPECT_EQ(Demo().usable_images, 13);
  EXPECT_LT(Demo().error_mean, Demo().nominal_error_mean / 3);
  EXPECT_GE(Demo().within_3sigma, 0.9);
  ASSERT_TRUE(Demo().calibration.validation.has_value());
  EXPECT_LT(Demo().calibration.validation->after.position_rms, Demo().calibration.validation->before.position_rms);
  // 5 steps, the plan line, 12 calibration lines (5 of them from pixels: fit, fx, fy, σ, two-stage
  // validation; one of camera-frame residuals; the worst image's closure)
  EXPECT_EQ(Notes().size(), 18u);
  EXPECT_THAT(Notes().front(), HasSubstr("[1/5 "));
  EXPECT_TRUE(std::filesystem::exists(Demo().report));
}

// The report on disk is the typed result the demo returned.
TEST_F(DemoSession, ReportJsonIsTheReturnedReport) {
  StatusOr<CalibrationReport> stored = LoadCalibrationReport(CalibrationReportPath(Session()));
  ASSERT_TRUE(stored.ok()) << stored.status().message();
  EXPECT_EQ(ToJson(*stored), ToJson(Demo().calibration));
}

// A second run keeps the measurements and gives the same parameters.
TEST_F(DemoSession, RecalibrationIsRepeatable) {
  std::vector<std::string> stages;
  JobHooks hooks;
  hooks.stage = [&](const std::string& stage) { stages.push_back(stage); };
  StatusOr<CalibrationReport> again = CalibrateSession({Session()}, hooks);
  ASSERT_TRUE(again.ok()) << again.status().message();
  const std::vector<std::string> expected = {"register and calibrate", "corners (calibration from pixels)",
                                             "calibrate from pixels"};
  EXPECT_EQ(stages, expected);  // nothing left to measure
  for (size_t k = 0; k < again->parameters.size(); ++k)
    EXPECT_NEAR(again->parameters[k].estimate, Demo().calibration.parameters[k].estimate, 1e-7);  // solver tolerance
}

// The default calibration is from pixels; --two-stage gives the other one,
// and both are honest about the truth's 3σ on the demo.
TEST_F(DemoSession, CalibratesFromPixelsByDefaultAndTwoStageOnRequest) {
  ASSERT_TRUE(Demo().calibration.from_pixels.has_value());
  const PixelFitSummary& pixels = *Demo().calibration.from_pixels;
  EXPECT_EQ(ToJson(Demo().calibration)["method"], "from-pixels");
  ASSERT_EQ(pixels.estimated.size(), 2u);  // fx, fy
  EXPECT_NEAR(pixels.estimated[0].estimate, pixels.estimated[0].file_value, 5 * pixels.estimated[0].sigma);
  EXPECT_LT(pixels.reprojection_rms_px, 0.2);
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(Session()) / "results" / "camera.yaml"));
  // Every corner of the fit, named by its legs.csv image (docs/calibration.md, "Per-corner diagnostics").
  const std::string corners_file = (std::filesystem::path(Session()) / "results" / "corner_residuals.csv").string();
  StatusOr<CornerResidualTable> corners = LoadCornerResiduals(corners_file);
  ASSERT_TRUE(corners.ok()) << corners.status().message();
  EXPECT_EQ(static_cast<int>(corners->corners.size()), pixels.corners);
  EXPECT_EQ(static_cast<int>(corners->images.size()), pixels.images);
  EXPECT_EQ(corners->images.front().rfind("view_", 0), 0u) << corners->images.front();
  CalibrateSessionRequest two_stage{Session()};
  two_stage.from_pixels.enabled = false;
  StatusOr<CalibrationReport> poses_only = CalibrateSession(two_stage);
  ASSERT_TRUE(poses_only.ok()) << poses_only.status().message();
  EXPECT_FALSE(poses_only->from_pixels.has_value());
  EXPECT_EQ(ToJson(*poses_only)["method"], "two-stage");
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(Session()) / "results" / "camera.yaml"));
  EXPECT_FALSE(std::filesystem::exists(corners_file));  // no fit to the corners, no residuals
  EXPECT_NEAR(poses_only->closure_position_rms, Demo().calibration.closure_position_rms,
              Demo().calibration.closure_position_rms);
  ASSERT_TRUE(CalibrateSession({Session()}).ok());  // back to the default for the other tests
}

TEST_F(DemoSession, CancelReturnsCancelledAndKeepsResults) {
  const std::string report = ReadTextFile(CalibrationReportPath(Session()));
  std::atomic<bool> cancel{true};
  StatusOr<CalibrationReport> cancelled = CalibrateSession({Session()}, JobHooks{{}, &cancel});
  ASSERT_FALSE(cancelled.ok());
  EXPECT_EQ(cancelled.status().kind(), StatusKind::kCancelled);
  EXPECT_EQ(ReadTextFile(CalibrationReportPath(Session())), report);
}

// The diagnosis runs on the 10 calibration images, and the summary and the
// page show it (its finding on clean demos: tests/cli/demo.sh; with 10
// images this seed's depth slope is 4.2 standard errors, the bound 4.28).
TEST_F(DemoSession, CameraFrameResidualsAreReported) {
  ASSERT_TRUE(Demo().calibration.camera_frame_residuals.has_value());
  const CameraFrameResiduals& r = *Demo().calibration.camera_frame_residuals;
  EXPECT_EQ(r.images, 10);
  EXPECT_EQ(r.fk_failed, 0);
  EXPECT_THAT(Notes(), Contains(HasSubstr("camera-frame residuals (cm, 10 images")));
  StatusOr<std::string> page = SessionReportHtml(Session());
  ASSERT_TRUE(page.ok()) << page.status().message();
  EXPECT_THAT(*page, HasSubstr("<h2>Camera-frame residuals</h2>"));
  EXPECT_THAT(*page, HasSubstr(" along the optical axis"));  // "No bias ..." or "A bias ..."
}

TEST_F(DemoSession, ReportPageRefusesToOverwriteWithoutForce) {
  TempDir dir;
  const std::string out = dir.File("page.html");
  ASSERT_TRUE(WriteSessionReport({Session(), out, false}).ok());
  StatusOr<std::string> again = WriteSessionReport({Session(), out, false});
  EXPECT_THAT(again.status().message(), HasSubstr("exists; use --force"));
  EXPECT_TRUE(WriteSessionReport({Session(), out, true}).ok());
}

TEST(CalibrateSession, MissingSessionIsBadInput) {
  TempDir dir;
  StatusOr<CalibrationReport> report = CalibrateSession({dir.File("nothing")});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.status().kind(), StatusKind::kBadInput);
  EXPECT_THAT(report.status().message(), HasSubstr("session.yaml"));
}

TEST(RunDemo, RefusesAUsersFolderAndBadCounts) {
  TempDir dir;
  std::filesystem::create_directories(dir.File("mine"));
  WriteTextFile(dir.File("mine/notes.txt"), "keep me");
  DemoRequest request;
  request.out = dir.File("mine");
  request.force = true;
  EXPECT_THAT(RunDemo(request).status().message(), HasSubstr("is not a demo folder"));
  EXPECT_EQ(ReadTextFile(dir.File("mine/notes.txt")), "keep me");
  request.poses = 3;
  EXPECT_EQ(RunDemo(request).status().kind(), StatusKind::kBadInput);
}

}  // namespace
}  // namespace hexcal::workflow

// Session folders for the workflow tests, written once here because several
// test files need the same one: a new camera session with nothing recorded,
// and demo sessions (workflow/demo.h). The demo is the slow part of the tests
// that use one (its full plan alone is about a minute under the sanitizers),
// so a suite that only reads or copies a calibrated session runs it once, in
// DemoSessionSuite.
//
//   TEST(ReadingsTable, ...) {
//     TempDir dir;
//     const std::string s = NewCameraSession(dir);
//   }
//
//   class DemoSession : public DemoSessionSuite<DemoSession> {
//    public:
//     static DemoRequest Request() { return SmallDemo(/*poses=*/10, /*holdout=*/3); }
//   };
//   TEST_F(DemoSession, CalibratesCloserToTheTruth) {
//     EXPECT_LT(Demo().error_mean, Demo().nominal_error_mean / 3);
//     EXPECT_TRUE(LoadCalibrationReport(CalibrationReportPath(Session())).ok());
//   }
//
// A suite's tests share its session: one that changes it copies Session() first.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/session.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/demo.h"

namespace hexcal::workflow {

// `dir`/s, a new session of inria-left-hand seen by the sim camera, the
// default board on its platform; no plan, images or readings yet.
inline std::string NewCameraSession(const hexcal::testing::TempDir& dir) {
  const std::string session = dir.File("s");
  EXPECT_TRUE(InitSession(session, {"inria-left-hand", kSimulatedCameraName, kDefaultTargetName}).ok());
  return session;
}

// `poses` planned poses, `holdout` random ones held out to validate.
inline DemoRequest SmallDemo(int poses, int holdout, uint64_t seed = 1) {
  DemoRequest request;
  request.poses = poses;
  request.holdout = holdout;
  request.seed = seed;
  return request;
}

// For tests of a calibrated session's files, not of the plan: the quick plan
// (random candidates, O1 alone) is a fraction of the full one's time.
inline DemoRequest QuickDemo(int poses, int holdout, uint64_t seed = 1) {
  DemoRequest request = SmallDemo(poses, holdout, seed);
  request.quick_plan = true;
  return request;
}

// The session `hexcal study` takes (demo --random-poses --holdout 0): random
// poses the camera sees, none held out.
inline DemoRequest RandomPosesDemo(int poses, uint64_t seed) {
  DemoRequest request = SmallDemo(poses, /*holdout=*/0, seed);
  request.random_poses = true;
  return request;
}

// A small session of `robot` in `out`, for the tests of the joint fits
// (from pixels, from points), which calibrate it both ways and compare.
inline DemoRequest FitComparisonDemo(const std::string& robot, const std::string& out) {
  DemoRequest request = QuickDemo(/*poses=*/16, /*holdout=*/4, /*seed=*/2);
  request.robot = robot;
  request.out = out;
  return request;
}

// RunDemo with its failure reported to the test, and an empty result then,
// so that the test's checks fail rather than the test stopping here.
inline DemoResult RunDemoInTest(const DemoRequest& request) {
  StatusOr<DemoResult> demo = RunDemo(request);
  EXPECT_TRUE(demo.ok()) << demo.status().message();
  return demo.ok() ? *demo : DemoResult{};
}

// The fixture of a suite whose tests share one demo session. `Suite` is the
// fixture deriving from it, with `static DemoRequest Request()`; `out` is
// set here, to a folder removed when the suite ends.
template <typename Suite>
class DemoSessionSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<hexcal::testing::TempDir>();
    DemoRequest request = Suite::Request();
    request.out = Session();
    JobHooks hooks;
    hooks.note = [](const std::string& line) { notes_.push_back(line); };
    StatusOr<DemoResult> demo = RunDemo(request, hooks);
    ASSERT_TRUE(demo.ok()) << demo.status().message();
    demo_ = *demo;
  }
  static void TearDownTestSuite() {
    demo_.reset();
    notes_.clear();
    dir_.reset();
  }

  // The session folder the demo recorded.
  static std::string Session() { return dir_->File("demo"); }
  // What the demo returned (throws, which fails the test, if it failed).
  static const DemoResult& Demo() { return demo_.value(); }
  // The lines the demo gave its hooks' `note`, in order.
  static const std::vector<std::string>& Notes() { return notes_; }

 private:
  inline static std::unique_ptr<hexcal::testing::TempDir> dir_;
  inline static std::optional<DemoResult> demo_;
  inline static std::vector<std::string> notes_;
};

}  // namespace hexcal::workflow

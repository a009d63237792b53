// What is measured again, and the status of each step, from the files'
// contents (workflow/session_measure.h, workflow/session_status.h).
#include "workflow/session_status.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/session.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_measure.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;

namespace fs = std::filesystem;

std::map<std::string, StepStatus> Steps(const std::string& dir) {
  StatusOr<SessionStatus> status = ReadSessionStatus(dir);
  EXPECT_TRUE(status.ok()) << status.status().message();
  std::map<std::string, StepStatus> steps;
  if (status.ok())
    for (const StepReport& step : status->steps) steps[step.step] = step.status;
  return steps;
}

std::vector<std::string> ImagesWithReadings(const std::string& dir) {
  std::vector<std::string> images;
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(dir);
  EXPECT_TRUE(rows.ok()) << rows.status().message();
  if (rows.ok())
    for (const LegsRow& row : *rows) images.push_back(row.image);
  return images;
}

TEST(SessionMeasure, NewIntrinsicsMeasureEveryImageAgainAndAReplacedImageItself) {
  TempDir dir;
  DemoRequest demo;
  demo.out = dir.File("demo");
  demo.poses = 8;
  demo.holdout = 2;
  ASSERT_TRUE(RunDemo(demo).ok());
  const std::string s = demo.out;
  for (const auto& [step, status] : Steps(s)) EXPECT_EQ(status, StepStatus::kDone) << step;

  // New intrinsics: a camera file with another focal length.
  StatusOr<SessionConfig> loaded = LoadSessionConfig(s);
  ASSERT_TRUE(loaded.ok());
  SessionConfig config = *loaded;
  StatusOr<Camera> old_camera = LoadCamera(ResolveSessionFile(s, config.camera));
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(s, config.target));
  ASSERT_TRUE(old_camera.ok() && target.ok());
  Camera camera = *old_camera;
  camera.fx *= 1.01;
  ASSERT_TRUE(SaveCamera(camera, s + "/camera.yaml").ok());
  config.camera = "camera.yaml";
  ASSERT_TRUE(SaveSessionConfig(s, config).ok());
  const std::vector<std::string> images = ImagesWithReadings(s);
  StatusOr<MeasureState> state = SessionMeasureState(s, images);
  ASSERT_TRUE(state.ok()) << state.status().message();
  EXPECT_EQ(state->to_measure.size(), images.size());
  EXPECT_EQ(state->reason, "the camera changed since the images were measured");
  EXPECT_EQ(Steps(s)["measure"], StepStatus::kStale);
  EXPECT_EQ(Steps(s)["calibrate"], StepStatus::kStale);

  const std::string before = ReadTextFile(s + "/measurements.csv");
  ASSERT_TRUE(CalibrateSession({s}).ok());
  EXPECT_NE(ReadTextFile(s + "/measurements.csv"), before);  // measured with the new camera, not reused
  for (const auto& [step, status] : Steps(s)) EXPECT_EQ(status, StepStatus::kDone) << step;

  // One image replaced under its name: that image only.
  fs::copy_file(s + "/images/" + images[1], s + "/images/" + images[0], fs::copy_options::overwrite_existing);
  state = SessionMeasureState(s, images);
  ASSERT_TRUE(state.ok());
  EXPECT_EQ(state->to_measure, std::vector<std::string>{images[0]});
  StatusOr<SessionMeasurements> measured = MeasureSessionImages(s, images, camera, *target, {}, {});
  ASSERT_TRUE(measured.ok()) << measured.status().message();
  EXPECT_EQ(measured->measured, 1);
  EXPECT_EQ(measured->reused, static_cast<int>(images.size()) - 1);
}

TEST(SessionStatus, AMissingSessionIsAnErrorAndAnEmptyOneIsTodo) {
  TempDir dir;
  EXPECT_FALSE(ReadSessionStatus(dir.File("none")).ok());
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.camera = kSimulatedCameraName;
  config.target = "aprilgrid-6x6";
  ASSERT_TRUE(InitSession(dir.File("s"), config).ok());
  std::map<std::string, StepStatus> steps = Steps(dir.File("s"));
  EXPECT_EQ(steps["robot"], StepStatus::kDone);
  for (const char* step : {"plan", "readings", "measure", "calibrate", "validate"})
    EXPECT_EQ(steps[step], StepStatus::kTodo) << step;
  StatusOr<SessionStatus> status = ReadSessionStatus(dir.File("s"));
  ASSERT_TRUE(status.ok());
  EXPECT_NE(FormatSessionStatus(*status).find("no legs.csv"), std::string::npos);
}

}  // namespace
}  // namespace hexcal::workflow

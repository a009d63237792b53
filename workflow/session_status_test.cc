// What is measured again, and the status of each step, from the files'
// contents (workflow/session_measure.h, workflow/session_status.h).
#include "workflow/session_status.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/acquire_step.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_edits.h"
#include "workflow/plan_step.h"
#include "workflow/session_measure.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

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


// One demo session, copied for each kind of change below: each test changes
// one input and checks every step's state and its reason.
class StatusAfterChange : public DemoSessionSuite<StatusAfterChange> {
 public:
  static DemoRequest Request() { return QuickDemo(/*poses=*/8, /*holdout=*/2); }

 protected:
  void SetUp() override {
    fs::copy(Session(), s_, fs::copy_options::recursive);
    for (const auto& [step, status] : Steps(s_)) ASSERT_EQ(status, StepStatus::kDone) << step;
  }
  SessionConfig Config() const {
    StatusOr<SessionConfig> config = LoadSessionConfig(s_);
    EXPECT_TRUE(config.ok());
    return config.ok() ? *config : SessionConfig{};
  }
  std::string Why(const std::string& step) const {
    StatusOr<SessionStatus> status = ReadSessionStatus(s_);
    if (status.ok())
      for (const StepReport& report : status->steps)
        if (report.step == step) return report.detail;
    return "";
  }
  // Steps expected to be other than done; every other step must be done.
  void ExpectOnly(const std::map<std::string, StepStatus>& changed) const {
    for (const auto& [step, status] : Steps(s_)) {
      const auto found = changed.find(step);
      EXPECT_EQ(status, found == changed.end() ? StepStatus::kDone : found->second) << step << ": " << Why(step);
    }
  }

  TempDir dir_;
  const std::string s_ = dir_.File("s");
};

// The suite's demo session (one RunDemo for every test: it is most of the
// suite's time under the sanitizers).
TEST_F(StatusAfterChange, NewIntrinsicsMeasureEveryImageAgainAndAReplacedImageItself) {
  const std::string s = s_;

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

  const std::string before = ReadTextFile(s + "/camera_poses.csv");
  ASSERT_TRUE(CalibrateSession({s}).ok());
  EXPECT_NE(ReadTextFile(s + "/camera_poses.csv"), before);  // measured with the new camera, not reused
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

TEST_F(StatusAfterChange, ARobotThatCannotReachThePlanMakesPlanAndResultsStale) {
  SessionConfig config = Config();
  StatusOr<Robot> robot = LoadRobot(config.robot);
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(s_ + "/plan.csv");
  ASSERT_TRUE(robot.ok() && plan.ok());
  robot->legs[2].stroke_max = robot->legs[2].stroke_min + 1e-3;  // leg 3 barely moves now
  // The poses that need more of leg 3 (a boundary pose may sit at its minimum).
  int beyond = 0, first = 0;
  for (size_t k = 0; k < plan->size(); ++k)
    if (InverseKinematics(*robot, robot->PoseFromVector((*plan)[k]))[2] > robot->legs[2].stroke_max &&
        beyond++ == 0)
      first = static_cast<int>(k) + 1;
  ASSERT_GT(beyond, 0);
  ASSERT_TRUE(SaveRobot(*robot, s_ + "/robot.yaml").ok());
  config.robot = "robot.yaml";
  ASSERT_TRUE(SaveSessionConfig(s_, config).ok());
  ExpectOnly({{"plan", StepStatus::kStale}, {"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
  EXPECT_NE(Why("plan").find(std::to_string(beyond) + " of 8 poses unreachable"), std::string::npos) << Why("plan");
  EXPECT_NE(Why("plan").find("pose " + std::to_string(first) + " breaks stroke max L3"), std::string::npos)
      << Why("plan");
  EXPECT_NE(Why("calibrate").find("robot robot.yaml"), std::string::npos) << Why("calibrate");
}

TEST_F(StatusAfterChange, TheSameRobotInAnotherFileKeepsThePlan) {
  SessionConfig config = Config();
  StatusOr<Robot> robot = LoadRobot(config.robot);
  ASSERT_TRUE(robot.ok());
  ASSERT_TRUE(SaveRobot(*robot, s_ + "/robot.yaml").ok());
  config.robot = "robot.yaml";
  ASSERT_TRUE(SaveSessionConfig(s_, config).ok());
  // The plan is judged by its content, not by the robot file's date.
  ExpectOnly({{"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
}

TEST_F(StatusAfterChange, ANewTargetMakesMeasureAndResultsStale) {
  SessionConfig config = Config();
  StatusOr<Target> target = LoadTarget(config.target);
  ASSERT_TRUE(target.ok());
  target->tag_size *= 1.02;
  WriteTextFile(s_ + "/target.yaml", TargetToYaml(*target));
  config.target = "target.yaml";
  ASSERT_TRUE(SaveSessionConfig(s_, config).ok());
  ExpectOnly({{"measure", StepStatus::kStale}, {"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
  EXPECT_NE(Why("measure").find("the target changed"), std::string::npos) << Why("measure");
}

TEST_F(StatusAfterChange, ANewCameraMakesMeasureAndResultsStale) {
  SessionConfig config = Config();
  StatusOr<Camera> camera = LoadCamera(config.camera);
  ASSERT_TRUE(camera.ok());
  camera->cx += 2;
  ASSERT_TRUE(SaveCamera(*camera, s_ + "/camera.yaml").ok());
  config.camera = "camera.yaml";
  ASSERT_TRUE(SaveSessionConfig(s_, config).ok());
  ExpectOnly({{"measure", StepStatus::kStale}, {"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
  EXPECT_NE(Why("measure").find("the camera changed"), std::string::npos) << Why("measure");
}

TEST_F(StatusAfterChange, AnUnreachablePlanPoseIsNamedAndAReachableEditIsDone) {
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(s_ + "/plan.csv");
  StatusOr<Robot> robot = LoadRobot(Config().robot);
  ASSERT_TRUE(plan.ok() && robot.ok());
  const PlanningModel model{*robot, std::nullopt, std::nullopt};
  std::vector<Vector6d> poses = *plan;
  poses[2](2) += 1e4;  // pose 3 far above the workspace
  ASSERT_TRUE(WritePlanCsv(s_ + "/plan.csv", model, poses).ok());
  ExpectOnly({{"plan", StepStatus::kStale}});  // the calibration does not read the plan
  EXPECT_NE(Why("plan").find("1 of 8 poses unreachable"), std::string::npos) << Why("plan");
  EXPECT_NE(Why("plan").find("pose 3 breaks"), std::string::npos) << Why("plan");
  poses.erase(poses.begin() + 2);
  ASSERT_TRUE(WritePlanCsv(s_ + "/plan.csv", model, poses).ok());
  ExpectOnly({});
}

TEST_F(StatusAfterChange, AnEditedReadingMakesOnlyTheResultsStale) {
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok());
  const LegsRow& first = rows->front();
  ASSERT_TRUE(ApplyLegsEdit(s_, LegsEdit::SetReading(first.image, 0, first.legs[0], first.legs[0] + 0.01)).status.ok());
  ExpectOnly({{"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
  EXPECT_NE(Why("calibrate").find("legs.csv changed"), std::string::npos) << Why("calibrate");
}

TEST_F(StatusAfterChange, AReplacedImageIsMeasuredAgainAlone) {
  const std::vector<std::string> images = ImagesWithReadings(s_);
  fs::copy_file(s_ + "/images/" + images[1], s_ + "/images/" + images[0], fs::copy_options::overwrite_existing);
  ExpectOnly({{"measure", StepStatus::kStale}, {"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
  EXPECT_NE(Why("measure").find("1 of 10 to measure again"), std::string::npos) << Why("measure");
  EXPECT_NE(Why("calibrate").find("images/" + images[0]), std::string::npos) << Why("calibrate");
}

TEST_F(StatusAfterChange, AMeasurementsTableEditedByHandIsMeasuredAgain) {
  std::string table = ReadTextFile(s_ + "/camera_poses.csv");
  const size_t last_digit = table.find_last_of("0123456789");
  ASSERT_NE(last_digit, std::string::npos);
  table[last_digit] = table[last_digit] == '7' ? '8' : '7';
  WriteTextFile(s_ + "/camera_poses.csv", table);
  ExpectOnly({{"measure", StepStatus::kStale}});
  EXPECT_NE(Why("measure").find("changed by another program"), std::string::npos) << Why("measure");
  ASSERT_TRUE(CalibrateSession({s_}).ok());
  EXPECT_NE(ReadTextFile(s_ + "/camera_poses.csv"), table);
  ExpectOnly({});
}

TEST_F(StatusAfterChange, ANewNoiseModelMakesOnlyTheResultsStale) {
  SessionConfig config = Config();
  config.noise.leg *= 2;
  ASSERT_TRUE(SaveSessionConfig(s_, config).ok());
  ExpectOnly({{"calibrate", StepStatus::kStale}, {"validate", StepStatus::kStale}});
}

TEST_F(StatusAfterChange, AnAcquisitionOfThePlanBegunIsToDoUntilEveryPoseIsRecorded) {
  TempDir dir;
  const std::string fresh = dir.File("fresh");
  SessionConfig config = Config();
  config.base_from_camera.reset();
  config.platform_from_target.reset();
  ASSERT_TRUE(InitSession(fresh, config).ok());
  fs::copy_file(s_ + "/plan.csv", fresh + "/plan.csv");
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(fresh + "/plan.csv");
  StatusOr<Robot> robot = LoadRobot(config.robot);
  ASSERT_TRUE(plan.ok() && robot.ok());
  const std::vector<Vector6d> first(plan->begin(), plan->begin() + 3);
  ASSERT_TRUE(WritePlanCsv(dir.File("first.csv"), PlanningModel{*robot, std::nullopt, std::nullopt}, first).ok());
  AcquireRequest request;
  request.session = fresh;
  request.poses = dir.File("first.csv");
  ASSERT_TRUE(AcquirePlan(request).ok());
  StatusOr<SessionStatus> status = ReadSessionStatus(fresh);
  ASSERT_TRUE(status.ok());
  EXPECT_EQ(status->Find("readings")->status, StepStatus::kTodo);
  EXPECT_NE(status->Find("readings")->detail.find("3 of 8 planned poses recorded"), std::string::npos)
      << status->Find("readings")->detail;
  request.poses.clear();  // the plan: the rest
  ASSERT_TRUE(AcquirePlan(request).ok());
  status = ReadSessionStatus(fresh);
  ASSERT_TRUE(status.ok());
  EXPECT_EQ(status->Find("readings")->status, StepStatus::kDone) << status->Find("readings")->detail;
}

TEST_F(StatusAfterChange, TheJsonFormHasEveryStepByNameWithItsReason) {
  StatusOr<SessionStatus> status = ReadSessionStatus(s_);
  ASSERT_TRUE(status.ok());
  const nlohmann::json json = ToJson(*status);
  for (const char* step : {"robot", "plan", "readings", "measure", "calibrate", "validate"}) {
    EXPECT_EQ(json["steps"][step], "done") << step;
    EXPECT_TRUE(json["why"][step].is_string()) << step;
  }
}

}  // namespace
}  // namespace hexcal::workflow

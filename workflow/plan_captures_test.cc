// Captures belong to planned poses by content (workflow/plan_captures.h,
// issue 35): a new plan's pose 1 is not "recorded" by an old pose_0000.png;
// its capture gets a free name; the captures a new plan leaves are kept,
// archived or discarded.
#include "workflow/plan_captures.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/acquire_step.h"
#include "workflow/session_edits.h"
#include "workflow/session_status.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

namespace fs = std::filesystem;

const Vector6d kFirst = (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished();
const Vector6d kSecond = (Vector6d() << 1, -0.5, 53, 2, -1, 4).finished();
const Vector6d kThird = (Vector6d() << -1, 0.8, 54, -2, 2, -3).finished();

std::string PlanText(const std::vector<Vector6d>& poses) {
  std::string text = "x,y,z,q1,q2,q3\n";
  for (const Vector6d& p : poses) {
    for (int k = 0; k < 6; ++k) text += (k ? "," : "") + FormatNumber(p[k]);
    text += "\n";
  }
  return text;
}

std::string MakeSession(const TempDir& dir, const std::vector<Vector6d>& plan) {
  const std::string session = dir.File("s");
  SessionConfig config{"inria-left-hand", kSimulatedCameraName, kDefaultTargetName};
  config.noise.leg = 0.001;
  EXPECT_TRUE(InitSession(session, config).ok());
  WriteTextFile(session + "/plan.csv", PlanText(plan));
  return session;
}

ReadingCheck Check(const std::string& session) {
  StatusOr<ReadingCheck> check = SessionReadingCheck(session);
  EXPECT_TRUE(check.ok());
  return *check;
}

std::vector<ReadingsRow> Rows(const std::string& session) {
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(session);
  EXPECT_TRUE(rows.ok()) << rows.status().message();
  return rows.ok() ? *rows : std::vector<ReadingsRow>{};
}

// A capture as the Acquire step records it: the nominal IK readings and the commanded pose.
void Capture(const std::string& session, const std::string& image, const Vector6d& pose, bool commanded = true) {
  const ReadingCheck check = Check(session);
  LegsRow row;
  row.image = image;
  row.legs = InverseKinematics(check.robot, check.robot.PoseFromVector(pose));
  if (commanded) row.commanded = pose;
  ASSERT_TRUE(RecordCaptureBytes(session, "png " + image, row).status.ok());
}

TEST(PlanCaptures, ANewPlansPoseIsNotRecordedByAnOldImageOfItsName) {
  TempDir dir;
  const std::string s = MakeSession(dir, {kFirst, kSecond});
  Capture(s, "pose_0000.png", kFirst);
  const ReadingCheck check = Check(s);
  EXPECT_EQ(CapturesOfPlan(check, {kFirst, kSecond}, Rows(s)), (std::vector<int>{0, -1}));
  // Replanned: pose 1 is now kThird; pose_0000.png was taken at kFirst.
  EXPECT_EQ(CapturesOfPlan(check, {kThird, kFirst}, Rows(s)), (std::vector<int>{-1, 0}));
  EXPECT_EQ(CaptureImageName(0, Rows(s)), "pose_0000_2.png");
  EXPECT_EQ(CaptureImageName(1, Rows(s)), "pose_0001.png");
  Capture(s, "pose_0000_2.png", kThird);
  EXPECT_EQ(CaptureImageName(0, Rows(s)), "pose_0000_3.png");
  EXPECT_EQ(CapturesOfPlan(check, {kThird, kFirst}, Rows(s)), (std::vector<int>{1, 0}));
}

TEST(PlanCaptures, ARowWithoutACommandedPoseCountsByNameAndReadings) {
  TempDir dir;
  const std::string s = MakeSession(dir, {kFirst, kSecond});
  Capture(s, "pose_0000.png", kFirst, /*commanded=*/false);
  Capture(s, "pose_0001.png", kThird, /*commanded=*/false);  // readings of another pose
  const ReadingCheck check = Check(s);
  EXPECT_EQ(CapturesOfPlan(check, {kFirst, kSecond}, Rows(s)), (std::vector<int>{0, -1}));
  EXPECT_EQ(CapturesOfPlan(check, {kSecond, kFirst}, Rows(s)), (std::vector<int>{-1, -1}));
}

TEST(PlanCaptures, CapturesANewPlanLeavesAreArchivedOrDiscarded) {
  TempDir dir;
  const std::string s = MakeSession(dir, {kFirst, kSecond});
  Capture(s, "pose_0000.png", kFirst);
  Capture(s, "pose_0001.png", kSecond);
  WriteTextFile(s + "/images/view.png", "a loaded image");
  const std::string legs = ReadTextFile(s + "/legs.csv");
  WriteTextFile(s + "/legs.csv", legs + "view.png,1,2,3,0.5,1.5,2.5,0,,,,,,\n");
  const ReadingCheck check = Check(s);
  // The new plan keeps kSecond (as its pose 1): only pose_0000.png is left.
  const std::vector<std::string> left = CapturesLeftByPlan(check, {kFirst, kSecond}, {kSecond, kThird}, Rows(s));
  EXPECT_EQ(left, std::vector<std::string>{"pose_0000.png"});

  StatusOr<std::string> archive = ArchiveCaptures(s, left);
  ASSERT_TRUE(archive.ok()) << archive.status().message();
  EXPECT_EQ(fs::path(*archive).parent_path(), fs::path(s) / "archive");
  EXPECT_TRUE(fs::exists(fs::path(*archive) / "images" / "pose_0000.png"));
  EXPECT_FALSE(fs::exists(s + "/images/pose_0000.png"));
  EXPECT_NE(ReadTextFile(*archive + "/legs.csv").find("pose_0000.png,"), std::string::npos);
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s);  // the session still loads
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_EQ((*rows)[0].image, "pose_0001.png");
  EXPECT_EQ((*rows)[1].image, "view.png");

  ASSERT_TRUE(DiscardCaptures(s, {"pose_0001.png"}).ok());
  EXPECT_FALSE(fs::exists(s + "/images/pose_0001.png"));
  rows = LoadSessionLegs(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 1u);
  EXPECT_EQ((*rows)[0].image, "view.png");
}

// hexcal acquire after a new plan whose pose 1 differs, the old capture kept:
// pose 1 is acquired again under a free name, and the status counts by content.
TEST(PlanCaptures, AcquireAfterANewPlanRecordsItsPosesUnderFreeNames) {
  TempDir dir;
  const std::string s = MakeSession(dir, {kFirst, kSecond});
  Capture(s, "pose_0000.png", kFirst);
  Capture(s, "pose_0001.png", kSecond);
  WriteTextFile(s + "/plan.csv", PlanText({kThird, kSecond}));
  StatusOr<SessionStatus> status = ReadSessionStatus(s);
  ASSERT_TRUE(status.ok());
  EXPECT_NE(status->Find("readings")->detail.find("1 of 2 planned poses recorded"), std::string::npos)
      << status->Find("readings")->detail;
  AcquireRequest request{s};
  StatusOr<AcquireResult> run = AcquirePlan(request);
  ASSERT_TRUE(run.ok()) << run.status().message();
  ASSERT_EQ(run->poses.size(), 2u);
  EXPECT_EQ(run->poses[0].state, PoseState::kRecorded);
  EXPECT_EQ(run->poses[0].image, "pose_0000_2.png");
  EXPECT_EQ(run->poses[1].state, PoseState::kAlreadyRecorded);
  EXPECT_EQ(run->poses[1].image, "pose_0001.png");
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 3u);
  ASSERT_TRUE(rows->back().commanded.has_value());
  EXPECT_TRUE(SameCommandedPose(*rows->back().commanded, kThird));
  status = ReadSessionStatus(s);
  ASSERT_TRUE(status.ok());
  EXPECT_EQ(status->Find("readings")->status, StepStatus::kDone) << status->Find("readings")->detail;
  EXPECT_EQ(status->Find("plan")->detail, "2 poses, all reachable by the robot");
}

}  // namespace
}  // namespace hexcal::workflow

// hexcal verify on the sim world (workflow/verify_step.h): with the session's
// frames set to the world's true ones, what the camera sees must be where the
// true robot put the platform, computed here independently from the world's
// truth; without registered frames the check is refused.
#include "workflow/verify_step.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/robot_io.h"
#include "core/session.h"
#include "sim/sim_world.h"
#include "tests/test_support.h"
#include "vision/board_pose.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

constexpr const char* kPoses = "x,y,z,q1,q2,q3\n0,0,53.5,0,0,0\n1,-0.5,53,2,-1,4\n-1,0.8,54,-2,2,-3\n";

std::string MakeSession(const TempDir& dir) {
  const std::string session = dir.File("s");
  EXPECT_TRUE(InitSession(session, {"inria-left-hand", kSimulatedCameraName, kDefaultTargetName}).ok());
  WriteTextFile(dir.File("check.csv"), kPoses);
  return session;
}

TEST(Verify, ASessionWithoutRegisteredFramesIsRefused) {
  TempDir dir;
  VerifyRequest request{MakeSession(dir)};
  request.poses = dir.File("check.csv");
  StatusOr<VerifyResult> checked = VerifyPoses(request);
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.status().kind(), StatusKind::kBadInput);
  EXPECT_NE(checked.status().message().find("calibrate it first"), std::string::npos) << checked.status().message();
}

// The world of seed 1, as the sim controller will draw it; its true frames
// go into the session, as a perfect registration would put them.
std::shared_ptr<SimWorld> RegisterTrueFrames(const std::string& s) {
  StatusOr<std::shared_ptr<SimWorld>> world = SimWorld::ForSession(s, 1);
  EXPECT_TRUE(world.ok()) << world.status().message();
  StatusOr<SessionConfig> config = LoadSessionConfig(s);
  EXPECT_TRUE(config.ok());
  config->base_from_camera = (*world)->scene().base_from_camera;
  config->platform_from_target = (*world)->scene().platform_from_target;
  EXPECT_TRUE(SaveSessionConfig(s, *config).ok());
  return *world;
}

// verify writes nothing into the session (issue 33): not the sim world's
// truth, not frames into images/; kept frames are not replaced without force.
TEST(Verify, WritesNothingIntoTheSessionAndReplacesNoFrameUnasked) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  RegisterTrueFrames(s);
  VerifyRequest request{s};
  request.poses = dir.File("check.csv");
  request.settle_seconds = 0;
  request.images_out = s + "/images/../images/checks";
  StatusOr<VerifyResult> into_images = VerifyPoses(request);
  ASSERT_FALSE(into_images.ok());
  EXPECT_EQ(into_images.status().kind(), StatusKind::kBadInput);
  EXPECT_NE(into_images.status().message().find("the session's images/ folder"), std::string::npos)
      << into_images.status().message();

  request.images_out = dir.File("frames");
  std::filesystem::create_directories(dir.File("frames"));
  WriteTextFile(dir.File("frames/check_0001.png"), "an earlier frame");
  StatusOr<VerifyResult> over = VerifyPoses(request);
  ASSERT_FALSE(over.ok());
  EXPECT_NE(over.status().message().find("check_0001.png exists: use another folder, or --force to replace"),
            std::string::npos)
      << over.status().message();
  EXPECT_FALSE(std::filesystem::exists(dir.File("frames/check_0000.png")));  // refused before anything moved

  request.force = true;
  StatusOr<VerifyResult> forced = VerifyPoses(request);
  ASSERT_TRUE(forced.ok()) << forced.status().message();
  EXPECT_NE(ReadTextFile(dir.File("frames/check_0001.png")), "an earlier frame");
  EXPECT_FALSE(std::filesystem::exists(s + "/truth"));
  EXPECT_TRUE(std::filesystem::is_empty(s + "/images"));
}

TEST(Verify, TheCameraSeesWhereTheTrueRobotPutThePlatform) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  std::shared_ptr<SimWorld> world_ptr = RegisterTrueFrames(s);
  std::shared_ptr<SimWorld>* world = &world_ptr;

  VerifyRequest request{s};
  request.poses = dir.File("check.csv");
  request.settle_seconds = 0;
  StatusOr<VerifyResult> checked = VerifyPoses(request);
  ASSERT_TRUE(checked.ok()) << checked.status().message();
  ASSERT_EQ(checked->Seen(), 3) << FormatVerifySummary(*checked);
  const Robot& nominal = (*world)->scene().nominal;
  for (const PoseCheck& check : checked->poses) {
    ASSERT_TRUE((*world)->Command(check.commanded).ok());
    const Pose truth = (*world)->ActualPose();  // the true robot's FK of the nominal IK
    const Pose seen = nominal.PoseFromVector(*check.seen);
    EXPECT_LT((seen.position - truth.position).norm(), 0.01) << "pose " << check.index;
    EXPECT_LT(RotationLog(truth.rotation.transpose() * seen.rotation).norm() * 180 / M_PI, 0.05);
    // The error reported is the true robot's departure from the command.
    const double true_error = (truth.position - nominal.PoseFromVector(check.commanded).position).norm();
    EXPECT_NEAR(check.position_error, true_error, 0.01) << "pose " << check.index;
    EXPECT_GT(true_error, 0.02);  // the hidden robot is ±0.5 mm off in every parameter: visible
  }
  EXPECT_NE(FormatVerifySummary(*checked).find("commanded against seen: position RMS"), std::string::npos);
  EXPECT_EQ(ToJson(*checked)["seen"], 3);
}

}  // namespace
}  // namespace hexcal::workflow

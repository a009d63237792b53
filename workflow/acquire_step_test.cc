// The Acquire step on the sim world and on files (workflow/acquire_step.h,
// docs/acquisition.md): images and rows recorded together, resume after a
// cancel or a kill, a failing pose reported while the run goes on, and URL
// errors that name the accepted forms.
#include "workflow/acquire_step.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/sim_world.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

namespace fs = std::filesystem;

// Poses around the centre of inria-left-hand's sampling box, where the sim
// camera (70 cm above) sees the whole board. Row 2 of `with_unreachable` is
// far above the workspace.
std::string MakeSession(const TempDir& dir, bool with_unreachable = false) {
  const std::string session = dir.File("s");
  EXPECT_TRUE(InitSession(session, {"inria-left-hand", kSimulatedCameraName, kDefaultTargetName}).ok());
  WriteTextFile(session + "/plan.csv", std::string("x,y,z,q1,q2,q3\n") + "0,0,53.5,0,0,0\n" + "1,-0.5,53,2,-1,4\n" +
                                           (with_unreachable ? "0,0,500,0,0,0\n" : "-1,0.8,54,-2,2,-3\n") +
                                           "0.5,1,53.8,1,1.5,-2\n");
  return session;
}

StatusOr<std::vector<LegsRow>> Rows(const std::string& session) { return LoadSessionLegs(session); }

TEST(AcquireStep, SimRunRecordsEveryPoseWithItsReadings) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  AcquireRequest request{s};
  request.options.holdout_every = 2;
  StatusOr<AcquireResult> run = AcquirePlan(request);
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->Count(PoseState::kRecorded), 4) << FormatAcquireSummary(*run);
  StatusOr<std::vector<LegsRow>> rows = Rows(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 4u);
  EXPECT_EQ((*rows)[3].image, "pose_0003.png");
  EXPECT_FALSE((*rows)[0].holdout);
  EXPECT_TRUE((*rows)[1].holdout);
  // The readings are the nominal IK of the commanded pose (what the
  // controller drives) plus the sensor noise of ±noise.leg (0.001 cm).
  const Robot nominal = *LoadRobot("inria-left-hand");
  Vector6d second;
  second << 1, -0.5, 53, 2, -1, 4;
  const LegReadings driven = InverseKinematics(nominal, nominal.PoseFromVector(second));
  EXPECT_LE(((*rows)[1].legs - driven).cwiseAbs().maxCoeff(), 0.001 + 1e-12);
  EXPECT_TRUE(fs::exists(s + "/truth/robot.yaml"));
  const cv::Mat image = cv::imread(s + "/images/pose_0000.png", cv::IMREAD_UNCHANGED);
  EXPECT_EQ(image.cols, 1024);
  EXPECT_EQ(image.rows, 768);
  EXPECT_NE(ToJson(*run).dump().find("\"recorded\":4"), std::string::npos);
}

TEST(AcquireStep, ACancelledRunResumesWhereItStopped) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  std::atomic<bool> cancel{false};
  JobHooks hooks([&](int done, int) { cancel = cancel || done == 2; }, &cancel);
  StatusOr<AcquireResult> first = AcquirePlan(AcquireRequest{s}, hooks);
  ASSERT_FALSE(first.ok());
  EXPECT_TRUE(first.status().cancelled());
  ASSERT_EQ(Rows(s)->size(), 2u);

  StatusOr<AcquireResult> second = AcquirePlan(AcquireRequest{s});
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_EQ(second->Count(PoseState::kAlreadyRecorded), 2);
  EXPECT_EQ(second->Count(PoseState::kRecorded), 2);
  StatusOr<std::vector<LegsRow>> rows = Rows(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();  // no image twice, none without a row
  EXPECT_EQ(rows->size(), 4u);
}

TEST(AcquireStep, AnImageLeftWithoutItsRowByAKillIsRecordedAgain) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  WriteTextFile(s + "/images/pose_0001.png", "half a capture");
  std::vector<std::string> notes;
  JobHooks hooks;
  hooks.note = [&](const std::string& line) { notes.push_back(line); };
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s}, hooks);
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->Count(PoseState::kRecorded), 4) << FormatAcquireSummary(*run);
  EXPECT_FALSE(cv::imread(s + "/images/pose_0001.png").empty());
  const auto noted = std::find_if(notes.begin(), notes.end(), [](const std::string& line) {
    return line.find("images/pose_0001.png had no row in legs.csv") != std::string::npos;
  });
  EXPECT_NE(noted, notes.end());
}

TEST(AcquireStep, AnUnreachablePoseFailsAndTheRunGoesOn) {
  TempDir dir;
  const std::string s = MakeSession(dir, /*with_unreachable=*/true);
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s});
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->Count(PoseState::kRecorded), 3);
  ASSERT_EQ(run->poses[2].state, PoseState::kFailed);
  EXPECT_NE(run->poses[2].error.find("out of the robot's workspace"), std::string::npos) << run->poses[2].error;
  EXPECT_NE(FormatAcquireSummary(*run).find("failed: pose_0002.png"), std::string::npos);
  EXPECT_EQ(Rows(s)->size(), 3u);
}

// A camera that drops its first frame, as a real one sometimes does.
class DropsFirstFrame final : public FrameSource {
 public:
  explicit DropsFirstFrame(std::unique_ptr<FrameSource> camera) : camera_(std::move(camera)) {}
  StatusOr<cv::Mat> Grab(std::chrono::milliseconds timeout) override {
    if (grabs_++ == 0) return Status::Failed("test camera: dropped frame");
    return camera_->Grab(timeout);
  }
  std::string Describe() const override { return "test camera"; }

 private:
  std::unique_ptr<FrameSource> camera_;
  int grabs_ = 0;
};

TEST(AcquireStep, AFrameThatFailsOnceFailsOnePoseAndTheNextRunRetriesIt) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(s, "sim", "sim", 1);
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  DropsFirstFrame camera(std::move(rig->camera));
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s}, *rig->controller, camera);
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->poses[0].state, PoseState::kFailed);
  EXPECT_EQ(run->poses[0].error, "test camera: dropped frame");
  EXPECT_EQ(run->Count(PoseState::kRecorded), 3);
  StatusOr<AcquireResult> retry = AcquirePlan(AcquireRequest{s}, *rig->controller, camera);
  ASSERT_TRUE(retry.ok()) << retry.status().message();
  EXPECT_EQ(retry->poses[0].state, PoseState::kRecorded);
  EXPECT_EQ(Rows(s)->size(), 4u);
}

TEST(AcquireStep, ResumingWithAnotherSeedIsRefused) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  ASSERT_TRUE(OpenAcquisitionRig(s, "sim", "sim", 1).ok());
  StatusOr<AcquisitionRig> other = OpenAcquisitionRig(s, "sim", "sim", 2);
  ASSERT_FALSE(other.ok());
  EXPECT_NE(other.status().message().find("another --seed than 2"), std::string::npos) << other.status().message();
}

TEST(AcquireStep, OnePoseAtATimeRefusesARecordedPose) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(s, "sim", "sim", 1);
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  const Vector6d pose = (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished();
  StatusOr<PoseRecord> first = AcquirePose(s, 7, pose, *rig->controller, *rig->camera, {});
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->image, "pose_0007.png");
  StatusOr<PoseRecord> again = AcquirePose(s, 7, pose, *rig->controller, *rig->camera, {});
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.status().message().find("pose_0007.png is recorded already"), std::string::npos);
}

TEST(FrameSource, AnImageFileGivesTheSameFrameEveryTime) {
  TempDir dir;
  const std::string file = dir.File("still.png");
  cv::Mat image(48, 64, CV_8UC1, cv::Scalar(90));
  image(cv::Rect(10, 10, 20, 20)) = 200;
  ASSERT_TRUE(cv::imwrite(file, image));
  StatusOr<std::unique_ptr<FrameSource>> source = OpenFrameSource("file:" + file);
  ASSERT_TRUE(source.ok()) << source.status().message();
  for (int k = 0; k < 2; ++k) {
    StatusOr<cv::Mat> frame = (*source)->Grab(std::chrono::milliseconds(100));
    ASSERT_TRUE(frame.ok()) << frame.status().message();
    EXPECT_EQ(cv::norm(*frame, image, cv::NORM_INF), 0);
  }
  EXPECT_EQ((*source)->SetExposure(1000).kind(), StatusKind::kBadInput);
}

TEST(FrameSource, AVideoFileGivesItsFramesThenNamesItsEnd) {
  TempDir dir;
  const std::string file = dir.File("short.avi");
  {
    cv::VideoWriter writer(file, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48), false);
    ASSERT_TRUE(writer.isOpened());
    for (int k = 0; k < 3; ++k) writer.write(cv::Mat(48, 64, CV_8UC1, cv::Scalar(60 * k)));
  }
  StatusOr<std::unique_ptr<FrameSource>> source = OpenFrameSource("file:" + file);
  ASSERT_TRUE(source.ok()) << source.status().message();
  for (int k = 0; k < 3; ++k) {
    StatusOr<cv::Mat> frame = (*source)->Grab(std::chrono::seconds(5));
    ASSERT_TRUE(frame.ok()) << frame.status().message();
    EXPECT_EQ(frame->cols, 64);
  }
  StatusOr<cv::Mat> end = (*source)->Grab(std::chrono::seconds(5));
  ASSERT_FALSE(end.ok());
  EXPECT_NE(end.status().message().find("end of the video after 3 frames"), std::string::npos)
      << end.status().message();
}

TEST(FrameSource, UrlErrorsNameTheUrlAndTheAcceptedForms) {
  const auto message = [](const std::string& url) {
    StatusOr<std::unique_ptr<FrameSource>> source = OpenFrameSource(url);
    EXPECT_FALSE(source.ok()) << url;
    EXPECT_EQ(source.status().kind(), StatusKind::kBadInput) << url;
    return source.ok() ? std::string() : source.status().message();
  };
#ifdef HEXCAL_HAVE_ARAVIS
  // Opening cameras: aravis_frame_source_test.cc.
  EXPECT_NE(message("aravis:Fake_1?exposure=fast").find("camera 'aravis:Fake_1?exposure=fast': exposure 'fast' is not"),
            std::string::npos);
#else
  EXPECT_NE(message("aravis:Fake_1").find("this hexcal was built without Aravis (install libaravis-dev"),
            std::string::npos);
#endif
  EXPECT_NE(message("gige:cam").find("camera 'gige:cam': unknown kind 'gige'; accepted forms: sim, v4l2:N"),
            std::string::npos);
  EXPECT_NE(message("v4l2:x").find("expected a device number"), std::string::npos);
  EXPECT_NE(message("file:/no/such.png").find("no such file"), std::string::npos);
  EXPECT_NE(message("sim").find("--controller sim"), std::string::npos);
}

TEST(Controller, UrlErrorsNameTheUrlAndTheAcceptedForms) {
  StatusOr<std::unique_ptr<Controller>> linuxcnc = OpenController("linuxcnc://localhost");
  ASSERT_FALSE(linuxcnc.ok());
  EXPECT_NE(linuxcnc.status().message().find("controller 'linuxcnc://localhost': no host or no port"),
            std::string::npos);
  StatusOr<std::unique_ptr<Controller>> unknown = OpenController("robot");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("controller 'robot': unknown kind; accepted forms: sim"),
            std::string::npos);
}

}  // namespace
}  // namespace hexcal::workflow

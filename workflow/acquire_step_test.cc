// The Acquire step on the sim world and on files (workflow/acquire_step.h,
// docs/acquisition.md): images and rows recorded together, resume after a
// cancel or a kill, a failing pose reported while the run goes on, and URL
// errors that name the accepted forms.
#include "workflow/acquire_step.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "sim/sim_world.h"
#include "tests/test_support.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

namespace fs = std::filesystem;

// Poses around the centre of inria-left-hand's sampling box, where the sim
// camera (70 cm above) sees the whole board. Row 2 of `with_unreachable` is
// far above the workspace.
std::string MakeSession(const TempDir& dir, bool with_unreachable = false) {
  const std::string session = NewCameraSession(dir);
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
  // Rows come in the order the poses were visited (VisitOrder), nearest first.
  std::map<std::string, LegsRow> by_image;
  for (const LegsRow& row : *rows) by_image[row.image] = row;
  ASSERT_EQ(by_image.count("pose_0003.png"), 1u);
  EXPECT_FALSE(by_image["pose_0000.png"].holdout);
  EXPECT_TRUE(by_image["pose_0001.png"].holdout);
  // The readings are the nominal IK of the commanded pose (what the
  // controller drives) plus the sensor noise of ±noise.leg (0.001 cm).
  const Robot nominal = *LoadRobot("inria-left-hand");
  Vector6d second;
  second << 1, -0.5, 53, 2, -1, 4;
  const LegReadings driven = InverseKinematics(nominal, nominal.PoseFromVector(second));
  EXPECT_LE((by_image["pose_0001.png"].legs - driven).cwiseAbs().maxCoeff(), 0.001 + 1e-12);
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
  WriteTextFile(s + "/.acquire-pending", "pose_0001.png\n");  // the kill came between the two writes
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

// An image without its row that acquire did not write is an operator's: it
// stays, and its pose fails (before the machine moves) while the run goes on.
TEST(AcquireStep, AnOperatorsOwnImageIsNeverRemoved) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  WriteTextFile(s + "/images/pose_0002.png", "the operator's own picture");
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s});
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->Count(PoseState::kRecorded), 3);
  ASSERT_EQ(run->poses[2].state, PoseState::kFailed);
  EXPECT_NE(run->poses[2].error.find("images/pose_0002.png exists without a row in legs.csv and hexcal acquire did "
                                     "not write it"),
            std::string::npos)
      << run->poses[2].error;
  EXPECT_EQ(ReadTextFile(s + "/images/pose_0002.png"), "the operator's own picture");
  EXPECT_FALSE(fs::exists(s + "/.acquire-pending"));
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

// MakeSession's session with its sim machine and camera open (seed 1), for
// the tests that put a faulty device of their own in front of one of them.
class AcquireOnSimRig : public ::testing::Test {
 protected:
  void SetUp() override {
    StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(s_, "sim", "sim", 1);
    ASSERT_TRUE(rig.ok()) << rig.status().message();
    rig_ = std::move(*rig);
  }

  TempDir dir_;
  const std::string s_ = MakeSession(dir_);
  AcquisitionRig rig_;
};

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

TEST_F(AcquireOnSimRig, AFrameThatFailsOnceFailsOnePoseAndTheNextRunRetriesIt) {
  DropsFirstFrame camera(std::move(rig_.camera));
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s_}, *rig_.controller, camera);
  ASSERT_TRUE(run.ok()) << run.status().message();
  const int first = run->visit_order.at(0);
  EXPECT_EQ(run->poses[first].state, PoseState::kFailed);
  EXPECT_EQ(run->poses[first].error, "test camera: dropped frame");
  EXPECT_EQ(run->Count(PoseState::kRecorded), 3);
  StatusOr<AcquireResult> retry = AcquirePlan(AcquireRequest{s_}, *rig_.controller, camera);
  ASSERT_TRUE(retry.ok()) << retry.status().message();
  EXPECT_EQ(retry->visit_order, std::vector<int>{first});
  EXPECT_EQ(retry->poses[first].state, PoseState::kRecorded);
  EXPECT_EQ(Rows(s_)->size(), 4u);
}

TEST(AcquireStep, ResumingWithAnotherSeedIsRefused) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  ASSERT_TRUE(OpenAcquisitionRig(s, "sim", "sim", 1).ok());
  StatusOr<AcquisitionRig> other = OpenAcquisitionRig(s, "sim", "sim", 2);
  ASSERT_FALSE(other.ok());
  EXPECT_NE(other.status().message().find("another --seed than 2"), std::string::npos) << other.status().message();
}

TEST_F(AcquireOnSimRig, OnePoseAtATimeRefusesARecordedPose) {
  const Vector6d pose = (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished();
  StatusOr<PoseRecord> first = AcquirePose(s_, 7, pose, *rig_.controller, *rig_.camera, {});
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->image, "pose_0007.png");
  StatusOr<PoseRecord> again = AcquirePose(s_, 7, pose, *rig_.controller, *rig_.camera, {});
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.status().message().find("pose_0007.png is recorded already"), std::string::npos);
}

// A controller that moves as the sim one does but reports what a faulty one
// might (issue 33): `lie` turns the sim's readings at the commanded pose into
// the reported ones. It records the settle times it is asked to wait.
class LyingController final : public Controller {
 public:
  using Lie = std::function<LegReadings(const LegReadings& honest)>;
  LyingController(Controller& honest, Lie lie) : honest_(honest), lie_(std::move(lie)) {}
  Status MoveTo(const Vector6d& pose) override { return honest_.MoveTo(pose); }
  Status WaitSettled(double seconds) override {
    settles.push_back(seconds);
    return honest_.WaitSettled(seconds);
  }
  StatusOr<LegReadings> ReadLegs() override {
    StatusOr<LegReadings> honest = honest_.ReadLegs();
    if (!honest.ok()) return honest;
    return lie_(*honest);
  }
  std::string Describe() const override { return "lying controller"; }
  double DefaultSettleSeconds() const override { return 0.01; }
  std::vector<double> settles;

 private:
  Controller& honest_;
  Lie lie_;
};

// The faults: 1e12, a leg at −50 cm, inch-scaled readings, another
// pose's readings. Each stops the run with the pose, the leg and both values,
// and nothing (no row, no image) is recorded.
TEST(AcquireStep, ImplausibleReadingsStopTheRunAndNothingIsRecorded) {
  const Robot nominal = *LoadRobot("inria-left-hand");
  // Row 1 is visited first (nearest the centre of the sampling box, z = 53); row 2's readings there.
  const LegReadings elsewhere =
      InverseKinematics(nominal, nominal.PoseFromVector((Vector6d() << -1, 0.8, 54, -2, 2, -3).finished()));
  const std::vector<std::pair<LyingController::Lie, std::string>> faults = {
      {[](LegReadings legs) {
         legs[2] = 1e12;
         return legs;
       },
       "leg 3 read 1000000000000 cm, outside its stroke [0, 3.5] cm"},
      {[](LegReadings legs) {
         legs[0] = -50;
         return legs;
       },
       "leg 1 read -50 cm, outside its stroke [0, 3.5] cm"},
      {[&](const LegReadings& legs) {  // joints in inches taken for cm
         LegReadings scaled;
         for (int i = 0; i < kNumLegs; ++i)
           scaled[i] = (legs[i] + nominal.legs[i].offset) / 2.54 - nominal.legs[i].offset;
         return scaled;
       },
       "leg 1 read -"},
      {[&](const LegReadings&) { return elsewhere; }, "where the commanded pose needs"}};
  for (const auto& [lie, expected] : faults) {
    TempDir dir;
    const std::string s = MakeSession(dir);
    StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(s, "sim", "sim", 1);
    ASSERT_TRUE(rig.ok()) << rig.status().message();
    LyingController controller(*rig->controller, lie);
    StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s}, controller, *rig->camera);
    ASSERT_FALSE(run.ok()) << expected;
    EXPECT_EQ(run.status().kind(), StatusKind::kFailed);
    const std::string& message = run.status().message();
    EXPECT_NE(message.find("lying controller: pose_0001.png at (1, -0.5, 53, 2, -1, 4): "), std::string::npos)
        << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_NE(message.find("nothing recorded for this pose"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(s + "/legs.csv"));
    EXPECT_TRUE(fs::is_empty(s + "/images"));
  }
}

TEST_F(AcquireOnSimRig, AnotherPosesReadingsNameBothValuesAndTheTolerance) {
  // 0.01 cm too long: beyond 5 x the session's leg noise (0.001 cm).
  LyingController controller(*rig_.controller, [](LegReadings legs) {
    legs[4] += 0.01;
    return legs;
  });
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s_}, controller, *rig_.camera);
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.status().message().find("more than 0.005 cm (5 x the session's leg noise 0.001 cm)"), std::string::npos)
      << run.status().message();
  EXPECT_NE(run.status().message().find("leg 5 read "), std::string::npos) << run.status().message();
}

TEST_F(AcquireOnSimRig, TheSettleTimeIsTheControllersUnlessGiven) {
  LyingController controller(*rig_.controller, [](const LegReadings& legs) { return legs; });
  AcquireRequest request{s_};
  request.poses = s_ + "/plan.csv";
  StatusOr<AcquireResult> run = AcquirePlan(request, controller, *rig_.camera);
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(controller.settles, std::vector<double>(4, 0.01));
  EXPECT_EQ(run->settle_seconds, 0.01);
  fs::remove(s_ + "/legs.csv");
  for (const fs::directory_entry& image : fs::directory_iterator(s_ + "/images")) fs::remove(image.path());
  controller.settles.clear();
  request.options.settle_seconds = 0;
  ASSERT_TRUE(AcquirePlan(request, controller, *rig_.camera).ok());
  EXPECT_EQ(controller.settles, std::vector<double>(4, 0.0));
}

// A machine stuck in a move (time-out, stopped away from its target): the
// run stops after that pose instead of sending the next one.
class StuckController final : public Controller {
 public:
  Status MoveTo(const Vector6d&) override {
    ++moves;
    return Status::Ok();
  }
  Status WaitSettled(double) override { return Status::Failed("test machine: the move did not end"); }
  StatusOr<LegReadings> ReadLegs() override { return Status::Failed("not reached"); }
  std::string Describe() const override { return "stuck controller"; }
  double DefaultSettleSeconds() const override { return 0; }
  bool Usable() const override { return moves == 0; }
  int moves = 0;
};

TEST_F(AcquireOnSimRig, AMachineStuckInAMoveStopsTheRun) {
  StuckController controller;
  StatusOr<AcquireResult> run = AcquirePlan(AcquireRequest{s_}, controller, *rig_.camera);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.status().kind(), StatusKind::kFailed);
  EXPECT_NE(run.status().message().find("test machine: the move did not end; the run stops here"), std::string::npos)
      << run.status().message();
  EXPECT_EQ(controller.moves, 1);
  EXPECT_FALSE(fs::exists(s_ + "/legs.csv"));
}

// A session that cannot take the captures is refused before the controller
// is opened: the LinuxCNC URL points at a closed port, so an error about the
// connection would mean the machine had been tried (and powered on, homed).
TEST(AcquireStep, TheSessionIsCheckedBeforeTheMachineIsOpened) {
  TempDir dir;
  const std::string s = MakeSession(dir);
  ASSERT_TRUE(cv::imwrite(dir.File("still.png"), cv::Mat(8, 8, CV_8UC1, cv::Scalar(0))));
  AcquireRequest request{s, "linuxcnc://127.0.0.1:1", "file:" + dir.File("still.png")};
  WriteTextFile(s + "/legs.csv", "image,L1\n\"unclosed\n");
  StatusOr<AcquireResult> broken_legs = AcquirePlan(request);
  ASSERT_FALSE(broken_legs.ok());
  EXPECT_NE(broken_legs.status().message().find("legs.csv"), std::string::npos) << broken_legs.status().message();
  EXPECT_EQ(broken_legs.status().message().find("LinuxCNC"), std::string::npos) << broken_legs.status().message();

  fs::remove(s + "/legs.csv");
  fs::remove_all(s + "/images");
  WriteTextFile(s + "/images", "a file where the folder should be");
  StatusOr<AcquireResult> no_images = AcquirePlan(request);
  ASSERT_FALSE(no_images.ok());
  EXPECT_EQ(no_images.status().kind(), StatusKind::kBadInput);  // the session's own file, not the disk
  EXPECT_NE(no_images.status().message().find("cannot write a new file there"), std::string::npos)
      << no_images.status().message();
  EXPECT_EQ(ReadTextFile(s + "/images"), "a file where the folder should be");
}

// Nearest first from the start, in leg space: pure z moves from z = 53.5.
TEST(AcquireStep, PosesAreVisitedNearestFirst) {
  const Robot robot = *LoadRobot("inria-left-hand");
  std::vector<Vector6d> poses;
  for (const double z : {56.0, 51.0, 53.7, 55.0}) poses.push_back((Vector6d() << 0, 0, z, 0, 0, 0).finished());
  const Vector6d start = (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished();
  EXPECT_EQ(VisitOrder(robot, poses, start, {}), (std::vector<int>{2, 3, 0, 1}));
  EXPECT_EQ(VisitOrder(robot, poses, start, {false, false, false, true}), (std::vector<int>{2, 0, 1}));
  // The acquire step starts from the centre of the sampling box, where the sim machine starts.
  poses.insert(poses.begin() + 2, WorkspaceCentre(robot));
  EXPECT_EQ(VisitOrder(robot, poses, WorkspaceCentre(robot), {}).front(), 2);
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

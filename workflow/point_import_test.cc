// A tracker's export merged into a points session's points file (the GUI's
// Import points…), and the sim tracker beside the sim controller (its Sim
// tracker): the names the sets get, replacing a pose only when asked, each
// layout kept, and a demo session's sim world connecting.
#include "workflow/point_import.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/csv.h"
#include "core/point_fit.h"
#include "core/session.h"
#include "tests/test_support.h"
#include "workflow/acquire_step.h"
#include "workflow/demo.h"
#include "workflow/plan_captures.h"
#include "sim/point_demo_scene.h"
#include "sim/sim_world.h"

namespace hexcal::workflow {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using hexcal::testing::ReadTextFile;
using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;

constexpr double kSessionSigma = 0.002;  // cm

// A points session whose points file is `points` (not written when empty).
std::string PointsSession(const TempDir& temp, const std::string& points_text) {
  const std::string dir = temp.File("run");
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.instrument = Instrument::kPoints;
  config.points = "points.txt";
  config.point_sigma = kSessionSigma;
  EXPECT_TRUE(InitSession(dir, config).ok());
  if (!points_text.empty()) WriteTextFile(dir + "/points.txt", points_text);
  return dir;
}

// SpatialAnalyzer's export of one pose, as its software names the group.
const char* kOneGroup =
    "// SpatialAnalyzer ASCII export\n"
    "Collection::A Group1 R1 1 2 3\n"
    "Collection::A Group1 R2 4 5 6 0.001\n"
    "Collection::A Group1 R3 7 8 10\n";

TEST(PointImport, OneSetIsTheChosenPoseAndAPoseIsReplacedOnlyWhenAsked) {
  TempDir temp;
  const std::string dir = PointsSession(temp, "");  // no points file yet: the first export makes it
  WriteTextFile(temp.File("export.txt"), kOneGroup);
  StatusOr<PointImport> import = ReadPointImport(dir, temp.File("export.txt"), "pose_0003");
  ASSERT_TRUE(import.ok()) << import.status().message();
  ASSERT_EQ(import->sets.size(), 1u);
  EXPECT_EQ(import->sets[0].pose, "pose_0003");
  EXPECT_TRUE(import->replaced.empty());
  ASSERT_TRUE(WritePointImport(dir, *import, /*replace=*/false).ok());
  // A point without its own σ stays without: the session's applies (here 0.5 as the reader's default).
  StatusOr<PointSets> written = LoadPointFile(dir + "/points.txt", 0.5);
  ASSERT_TRUE(written.ok()) << written.status().message();
  ASSERT_EQ(written->size(), 1u);
  EXPECT_EQ((*written)[0].pose, "pose_0003");
  ASSERT_EQ((*written)[0].points.size(), 3u);
  EXPECT_EQ((*written)[0].points[0].sigma, 0.5);
  EXPECT_EQ((*written)[0].points[1].sigma, 0.001);
  EXPECT_EQ((*written)[0].points[2].position.z(), 10);

  // The same pose again: named as already there, refused unless replacing.
  WriteTextFile(temp.File("again.txt"), "c g R1 1 2 3.5\nc g R2 4 5 6\nc g R3 7 8 10\n");
  import = ReadPointImport(dir, temp.File("again.txt"), "pose_0003");
  ASSERT_TRUE(import.ok());
  EXPECT_THAT(import->replaced, ElementsAre("pose_0003"));
  const Status refused = WritePointImport(dir, *import, /*replace=*/false);
  EXPECT_FALSE(refused.ok());
  EXPECT_THAT(refused.message(), HasSubstr("points.txt has points of pose 'pose_0003' already"));
  ASSERT_TRUE(WritePointImport(dir, *import, /*replace=*/true).ok());
  written = LoadPointFile(dir + "/points.txt", 0.5);
  ASSERT_TRUE(written.ok());
  ASSERT_EQ(written->size(), 1u);
  EXPECT_EQ((*written)[0].points[0].position.z(), 3.5);
  EXPECT_THAT(ReadTextFile(dir + "/points.txt"), HasSubstr("collection group target x y z"));
}

TEST(PointImport, SeveralSetsKeepTheirNamesAndACsvFileStaysCsv) {
  TempDir temp;
  const std::string dir =
      PointsSession(temp, "pose,point,x,y,z,sigma\npose_0000,R1,1,1,1,0.003\npose_0000,R2,2,2,2,0.003\n");
  WriteTextFile(temp.File("two.txt"), "c pose_0001 R1 1 2 3\nc pose_0001 R2 4 5 6\nc pose_0002 R1 7 8 9\n");
  StatusOr<PointImport> import = ReadPointImport(dir, temp.File("two.txt"), "pose_0009");
  ASSERT_TRUE(import.ok()) << import.status().message();
  ASSERT_EQ(import->sets.size(), 2u);  // named by their groups, not the chosen pose
  EXPECT_EQ(import->sets[0].pose, "pose_0001");
  EXPECT_EQ(import->sets[1].pose, "pose_0002");
  ASSERT_TRUE(WritePointImport(dir, *import, false).ok());
  const std::string text = ReadTextFile(dir + "/points.txt");
  EXPECT_EQ(text.rfind("pose,point,x,y,z,sigma\n", 0), 0u) << text;
  // Its σ column holds the session's σ for the imported points, which had none.
  EXPECT_THAT(text, HasSubstr("pose_0001,R1,1,2,3,0.002\n"));
  StatusOr<PointSets> written = LoadPointFile(dir + "/points.txt", 1);
  ASSERT_TRUE(written.ok());
  EXPECT_EQ(written->size(), 3u);
  EXPECT_EQ((*written)[0].points[0].sigma, 0.003);
}

TEST(PointImport, RefusesWhatCannotBeAPointsSessionsPose) {
  TempDir temp;
  const std::string dir = PointsSession(temp, "");
  WriteTextFile(temp.File("spaces.csv"), "pose,point,x,y,z\npose 1,R1,1,2,3\nother,R1,1,2,3\n");
  StatusOr<PointImport> import = ReadPointImport(dir, temp.File("spaces.csv"), "pose_0001");
  ASSERT_FALSE(import.ok());
  EXPECT_THAT(import.status().message(), HasSubstr("spaces.csv: 'pose 1' cannot name a pose"));
  WriteTextFile(temp.File("broken.txt"), "c g R1 1 2\n");
  import = ReadPointImport(dir, temp.File("broken.txt"), "pose_0001");
  ASSERT_FALSE(import.ok());
  EXPECT_THAT(import.status().message(), HasSubstr("broken.txt:1: expected collection, group, target"));

  SessionConfig camera;
  camera.robot = "inria-left-hand";
  camera.camera = "sim-4.2mm-1024x768";
  camera.target = "aprilgrid-6x6";
  ASSERT_TRUE(InitSession(temp.File("camera"), camera).ok());
  WriteTextFile(temp.File("export.txt"), kOneGroup);
  import = ReadPointImport(temp.File("camera"), temp.File("export.txt"), "pose_0001");
  ASSERT_FALSE(import.ok());
  EXPECT_THAT(import.status().message(), HasSubstr("not a points session"));
}

// The sim controller of a points session drives the world `hexcal demo
// --instrument points` draws: a demo session of the same seed connects (its
// truth matches), and the sim tracker sees the demo's reflectors rigidly
// moved, each coordinate with the session's σ.
TEST(SimTracker, MeasuresTheReflectorsWhereTheSimPlatformIs) {
  TempDir temp;
  DemoRequest request;
  request.out = temp.File("demo");
  request.instrument = Instrument::kPoints;
  request.quick_plan = true;
  request.poses = 12;
  request.holdout = 2;
  ASSERT_TRUE(RunDemo(request).ok());
  StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(request.out, "sim", "", request.seed);
  ASSERT_TRUE(rig.ok()) << rig.status().message();
  EXPECT_EQ(rig->camera, nullptr);
  ASSERT_NE(rig->sim, nullptr);
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(SessionPaths(request.out).plan);
  ASSERT_TRUE(plan.ok());
  ASSERT_TRUE(rig->controller->MoveTo((*plan)[4]).ok());
  const PointSet seen = SimTrackerMeasure(*rig->sim, kSessionSigma, AcquiredPoseName(4), 1);
  EXPECT_EQ(seen.pose, "pose_0004");
  const std::vector<NamedPoint> reflectors = DemoReflectors(rig->sim->scene());
  ASSERT_EQ(seen.points.size(), reflectors.size());
  StatusOr<PointFit> fit = FitPointPose(reflectors, seen.points);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_LT(fit->rms, 5 * kSessionSigma);
  EXPECT_GT(fit->rms, 0);  // with noise
  for (const NamedPoint& point : seen.points) EXPECT_EQ(point.sigma, kSessionSigma);
  // Another measurement draws other noise.
  const PointSet again = SimTrackerMeasure(*rig->sim, kSessionSigma, "pose_0004", 2);
  EXPECT_NE(again.points[0].position, seen.points[0].position);
}

}  // namespace
}  // namespace hexcal::workflow

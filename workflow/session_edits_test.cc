// The operator's edits applied to the files as they are on disk, and results/
// as one unit (workflow/session_edits.h, session/session_results.h).
#include "workflow/session_edits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "session/readings_table.h"
#include "session/session_results.h"
#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

namespace fs = std::filesystem;

// A session with one image (any bytes: edits and hashes never decode them).
std::string MakeSession(const TempDir& dir) {
  const std::string session = NewCameraSession(dir);
  WriteTextFile(session + "/images/a.png", "image a");
  WriteTextFile(session + "/legs.csv", "image,L1,L2,L3,L4,L5,L6,holdout\na.png,50,51,52,53,54,55,0\n");
  return session;
}

// Each test starts from MakeSession's session, in a folder of its own.
class SessionEdits : public ::testing::Test {
 protected:
  TempDir dir_;
  const std::string s_ = MakeSession(dir_);
};

TEST_F(SessionEdits, ACaptureTakenBackLeavesNeitherRowNorImage) {
  WriteTextFile(s_ + "/images/b.png", "image b");
  WriteTextFile(s_ + "/legs.csv", ReadTextFile(s_ + "/legs.csv") + "b.png,60,61,62,63,64,65,1\n");
  ASSERT_TRUE(RemoveCapture(s_, "a.png").ok());
  EXPECT_FALSE(fs::exists(s_ + "/images/a.png"));
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 1u);
  EXPECT_EQ((*rows)[0].image, "b.png");
  EXPECT_FALSE(RemoveCapture(s_, "a.png").ok());            // gone already
  EXPECT_FALSE(RemoveCapture(s_, "../session.yaml").ok());  // never outside images/
  EXPECT_TRUE(fs::exists(s_ + "/session.yaml"));
}

// A points session's legs.csv is keyed by `pose` (issue 38): the edits find
// and write that column, a new file gets it, captures (images) are refused,
// and the readings table has a blank row for each pose of the points file
// without readings.
TEST_F(SessionEdits, APointsSessionsRowsAreKeyedByPose) {
  const std::string s = dir_.File("p");  // beside the fixture's camera session
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.instrument = Instrument::kPoints;
  config.points = "points.csv";
  config.point_sigma = 0.002;
  ASSERT_TRUE(InitSession(s, config).ok());
  WriteTextFile(s + "/points.csv", "pose,point,x,y,z\np1,R1,0,0,0\np2,R1,0,0,0\np3,R1,0,0,0\n");
  LegsRow row;
  row.image = "p1";
  row.legs << 50, 51, 52, 53, 54, 55;
  ASSERT_TRUE(ApplyLegsEdit(s, LegsEdit::SetRow(row)).status.ok());
  EXPECT_EQ(ReadTextFile(s + "/legs.csv"), "pose,L1,L2,L3,L4,L5,L6,holdout\np1,50,51,52,53,54,55,0\n");
  ASSERT_TRUE(ApplyLegsEdit(s, LegsEdit::SetReading("p1", 2, 52, 52.5)).status.ok());
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ((*rows)[0].legs[2], 52.5);
  EXPECT_FALSE(ApplyLegsEdit(s, LegsEdit::SetReading("p9", 0, 50, 51)).status.ok());  // no such pose

  const EditOutcome capture = RecordCaptureBytes(s, "image", row);
  EXPECT_NE(capture.status.message().find("a points session has no images"), std::string::npos)
      << capture.status.message();
  EXPECT_FALSE(RemoveCapture(s, "a.png").ok());

  StatusOr<std::vector<ReadingsRow>> table = ReadReadingsTable(s);
  ASSERT_TRUE(table.ok()) << table.status().message();
  ASSERT_EQ(table->size(), 3u);  // p1 recorded, p2 and p3 to type
  EXPECT_TRUE((*table)[0].recorded && (*table)[0].image_present);
  EXPECT_EQ((*table)[1].image, "p2");
  EXPECT_FALSE((*table)[1].recorded);
}

TEST_F(SessionEdits, AnEditKeepsTheRowsAnotherProgramAppended) {
  // Another program appends b.png while the GUI shows only a.png.
  WriteTextFile(s_ + "/images/b.png", "image b");
  WriteTextFile(s_ + "/legs.csv", ReadTextFile(s_ + "/legs.csv") + "b.png,60,61,62,63,64,65,1\n");
  const EditOutcome done = ApplyLegsEdit(s_, LegsEdit::SetReading("a.png", 2, 52, 52.5));
  ASSERT_TRUE(done.status.ok()) << done.status.message();
  ASSERT_FALSE(done.conflict);
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_EQ((*rows)[0].legs[2], 52.5);
  EXPECT_EQ((*rows)[1].image, "b.png");
  EXPECT_EQ((*rows)[1].legs[5], 65);
  EXPECT_TRUE((*rows)[1].holdout);
}

TEST_F(SessionEdits, TheSameCellChangedOnDiskIsAConflictAndNothingIsWritten) {
  WriteTextFile(s_ + "/legs.csv", "image,L1,L2,L3,L4,L5,L6,holdout\na.png,50,51,52.2,53,54,55,0\n");
  const std::string on_disk = ReadTextFile(s_ + "/legs.csv");
  const EditOutcome clash = ApplyLegsEdit(s_, LegsEdit::SetReading("a.png", 2, 52, 52.5));
  ASSERT_TRUE(clash.status.ok());
  ASSERT_TRUE(clash.conflict);
  EXPECT_NE(clash.conflict_text.find("L3 of a.png is '52.2' on disk"), std::string::npos) << clash.conflict_text;
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), on_disk);
  EditOptions overwrite;
  overwrite.overwrite = true;
  EXPECT_FALSE(ApplyLegsEdit(s_, LegsEdit::SetReading("a.png", 2, 52, 52.5), overwrite).conflict);
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ((*rows)[0].legs[2], 52.5);
}

TEST_F(SessionEdits, ACaptureNeverReplacesRowsNorWritesOverAFileThatDoesNotParse) {
  LegsRow row;
  row.image = "a.png";
  EXPECT_TRUE(ApplyLegsEdit(s_, LegsEdit::SetRow(row)).conflict);  // a.png has readings already
  row.image = "b.png";
  row.legs << 1, 2, 3, 4, 5, 6;
  WriteTextFile(s_ + "/images/b.png", "image b");
  ASSERT_TRUE(ApplyLegsEdit(s_, LegsEdit::SetRow(row)).status.ok());
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ(rows->size(), 2u);
  // A legs.csv that does not load is refused, never replaced by one holding only the new row.
  WriteTextFile(s_ + "/legs.csv", "image,L1,L2\nbroken");
  row.image = "c.png";
  const EditOutcome refused = ApplyLegsEdit(s_, LegsEdit::SetRow(row));
  EXPECT_FALSE(refused.status.ok());
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), "image,L1,L2\nbroken");
}

TEST_F(SessionEdits, ACaptureBringsItsImageAndRowTogetherAndStaysInsideImages) {
  WriteTextFile(dir_.File("frame.png"), "a captured frame");
  LegsRow row;
  row.image = "b.png";
  row.legs << 1, 2, 3, 4, 5, 6;
  ASSERT_TRUE(RecordCapture(s_, dir_.File("frame.png"), row).status.ok());
  EXPECT_EQ(ReadTextFile(s_ + "/images/b.png"), "a captured frame");
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ(rows->size(), 2u);
  EXPECT_TRUE(RecordCapture(s_, dir_.File("frame.png"), row).conflict);  // b.png is there already
  row.image = "../escape.png";
  EXPECT_FALSE(RecordCapture(s_, dir_.File("frame.png"), row).status.ok());
  EXPECT_FALSE(fs::exists(dir_.File("escape.png")));
}

TEST_F(SessionEdits, ACaptureIsNeverWrittenThroughALinkOutOfTheSession) {
  TempDir elsewhere;
  fs::rename(s_ + "/images", dir_.File("moved"));
  fs::create_directory_symlink(elsewhere.path(), s_ + "/images");
  WriteTextFile(dir_.File("frame.png"), "frame");
  LegsRow row;
  row.image = "b.png";
  const EditOutcome refused = RecordCapture(s_, dir_.File("frame.png"), row);
  EXPECT_NE(refused.status.message().find("leads out of the session folder"), std::string::npos)
      << refused.status.message();
  EXPECT_FALSE(fs::exists(elsewhere.File("b.png")));
}

TEST_F(SessionEdits, ARowAddedToAFileWithoutHoldoutGetsTheColumnAndNaNIsRefused) {
  WriteTextFile(s_ + "/legs.csv", "image,L1,L2,L3,L4,L5,L6\na.png,50,51,52,53,54,55\n");
  WriteTextFile(s_ + "/images/b.png", "image b");
  LegsRow row;
  row.image = "b.png";
  row.legs << 1, 2, 3, 4, 5, 6;
  row.holdout = true;
  ASSERT_TRUE(ApplyLegsEdit(s_, LegsEdit::SetRow(row)).status.ok());
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_FALSE((*rows)[0].holdout);
  EXPECT_TRUE((*rows)[1].holdout);
  const std::string before = ReadTextFile(s_ + "/legs.csv");
  EXPECT_FALSE(ApplyLegsEdit(s_, LegsEdit::SetReading("a.png", 0, 50, std::nan(""))).status.ok());
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), before);
}

TEST_F(SessionEdits, AnImportThatDoesNotLoadKeepsTheOldReadings) {
  const std::string before = ReadTextFile(s_ + "/legs.csv");
  WriteTextFile(dir_.File("bad.csv"), "image,L1,L2,L3,L4,L5,L6\nmissing.png,1,2,3,4,5,6\n");
  const Status refused = ImportLegsFile(s_, dir_.File("bad.csv"));
  EXPECT_NE(refused.message().find("missing.png"), std::string::npos) << refused.message();
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), before);
  // Readings beyond the stroke (0..3.5 cm) are refused by line, image, leg and value.
  WriteTextFile(dir_.File("typo.csv"), "image,L1,L2,L3,L4,L5,L6\na.png,1,2,3,0.5,1.5,999999\n");
  const Status typo = ImportLegsFile(s_, dir_.File("typo.csv"));
  EXPECT_NE(typo.message().find("typo.csv:2: a.png: L6 = 999999 cm is outside leg 6's stroke"), std::string::npos)
      << typo.message();
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), before);
  WriteTextFile(dir_.File("good.csv"), "image,L1,L2,L3,L4,L5,L6\na.png,1,2,3,0.5,1.5,2.5\n");
  EXPECT_TRUE(ImportLegsFile(s_, dir_.File("good.csv")).ok());
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ((*rows)[0].legs[0], 1);
}

// A capture's commanded pose goes into legs.csv's commanded columns, empty for
// the other rows, and comes back from LoadSessionLegs. An import is checked
// against it: readings far from the pose's IK lengths are refused (issue 35).
TEST_F(SessionEdits, ACapturesCommandedPoseIsKeptAndImportsAreCheckedAgainstIt) {
  WriteTextFile(s_ + "/legs.csv", "image,L1,L2,L3,L4,L5,L6,holdout\na.png,1,2,3,0.5,1.5,2.5,0\n");
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  ASSERT_TRUE(robot.ok());
  const Vector6d pose = (Vector6d() << 1, -0.5, 53, 2, -1, 4).finished();
  LegsRow row;
  row.image = "pose_0000.png";
  row.legs = InverseKinematics(*robot, robot->PoseFromVector(pose));
  row.commanded = pose;
  ASSERT_TRUE(RecordCaptureBytes(s_, "png bytes", row).status.ok());
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(s_);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_FALSE((*rows)[0].commanded.has_value());
  ASSERT_TRUE((*rows)[1].commanded.has_value());
  EXPECT_EQ(*(*rows)[1].commanded, pose);  // exact: the shortest text that reads back the same
  EXPECT_NE(ReadTextFile(s_ + "/legs.csv").find("commanded_q3"), std::string::npos);

  // Half a commanded pose is named.
  const std::string before = ReadTextFile(s_ + "/legs.csv");
  std::string half = before;
  half.replace(half.rfind(",4\n"), 3, ",\n");
  WriteTextFile(dir_.File("half.csv"), half);
  EXPECT_NE(ImportLegsFile(s_, dir_.File("half.csv")).message().find("of its six cells"), std::string::npos);

  // An import without the commanded columns is checked against the session's.
  std::string moved = "image,L1,L2,L3,L4,L5,L6\na.png,1,2,3,0.5,1.5,2.5\npose_0000.png";
  for (int i = 0; i < kNumLegs; ++i) moved += "," + FormatNumber(row.legs[i] + (i == 2 ? 1.0 : 0.0));
  WriteTextFile(dir_.File("moved.csv"), moved + "\n");
  const Status far = ImportLegsFile(s_, dir_.File("moved.csv"));
  EXPECT_NE(far.message().find("moved.csv:3: pose_0000.png: L3 = "), std::string::npos) << far.message();
  EXPECT_NE(far.message().find("the commanded pose needs"), std::string::npos) << far.message();
  EXPECT_EQ(ReadTextFile(s_ + "/legs.csv"), before);
}

TEST_F(SessionEdits, APlanOrCameraChangedOnDiskIsAConflict) {
  const std::vector<Vector6d> theirs{Vector6d::Constant(1.0)};
  ASSERT_TRUE(ApplyPlanEdit(s_, {}, theirs).status.ok());  // another program's plan
  const EditOutcome clash = ApplyPlanEdit(s_, {}, {Vector6d::Zero(), Vector6d::Zero()});
  EXPECT_TRUE(clash.conflict) << clash.conflict_text;
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(s_ + "/plan.csv");
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_EQ(plan->size(), 1u);
  EXPECT_FALSE(ApplyPlanEdit(s_, theirs, {}).conflict);  // the operator deletes the plan they saw
  EXPECT_FALSE(fs::exists(s_ + "/plan.csv"));

  EXPECT_TRUE(ApplyCameraEdit(s_, "other.yaml", "mine.yaml").conflict);
  EXPECT_FALSE(ApplyCameraEdit(s_, kSimulatedCameraName, "mine.yaml").conflict);
  StatusOr<SessionConfig> config = LoadSessionConfig(s_);
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->camera, "mine.yaml");
}

// Records a quick demo's calibrated session in `out`, for the tests below
// that change its files.
Status RecordCalibratedSession(const std::string& out) {
  DemoRequest demo = QuickDemo(/*poses=*/8, /*holdout=*/2);
  demo.out = out;
  return RunDemo(demo).status();
}

// A reading far outside the stroke, or readings that fit no pose of the
// nominal robot, are named by image and legs.csv line, not "pose 1" (issue 35).
TEST(SessionCalibrate, ReadingsThatFitNoPoseAreNamedByImageAndLine) {
  TempDir dir;
  const std::string s = dir.File("demo");
  ASSERT_TRUE(RecordCalibratedSession(s).ok());
  StatusOr<CsvTable> table = ReadCsv(s + "/legs.csv");
  ASSERT_TRUE(table.ok());
  const std::string image = table->rows[1][0];  // line 3
  auto with_legs = [&](const std::vector<std::string>& values) {
    CsvTable changed = *table;
    for (size_t i = 0; i < values.size(); ++i) changed.rows[1][1 + i] = values[i];
    WriteTextFile(s + "/legs.csv", FormatCsv(changed.header, changed.rows));
  };
  with_legs({table->rows[1][1], table->rows[1][2], "999999"});
  StatusOr<CalibrationReport> run = CalibrateSession({s});
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.status().message().find(image + " (legs.csv line 3): L3 = 999999 cm is far outside leg 3's stroke"),
            std::string::npos)
      << run.status().message();
  // Within a stroke beyond each end (0..3.5 cm), but no pose has these lengths.
  with_legs({"6.9", "-3.4", "6.9", "-3.4", "6.9", "-3.4"});
  run = CalibrateSession({s});
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.status().message().find(image + " (legs.csv line 3): forward kinematics did not converge"),
            std::string::npos)
      << run.status().message();
  EXPECT_NE(run.status().message().find("L1..L6 = "), std::string::npos) << run.status().message();
}

TEST(SessionResults, ACalibrationWhoseInputsChangeUnderneathPublishesNothing) {
  TempDir dir;
  const std::string s = dir.File("demo");
  ASSERT_TRUE(RecordCalibratedSession(s).ok());
  StatusOr<SessionResults> before = LoadSessionResults(s);
  ASSERT_TRUE(before.ok()) << before.status().message();
  EXPECT_TRUE(before->changed_inputs.empty());
  const std::string report = ReadTextFile(CalibrationReportPath(s));
  // Another program rewrites legs.csv, without the lock, while the legs are fitted.
  JobHooks hooks;
  hooks.stage = [&](const std::string& stage) {
    if (stage == "register and calibrate") WriteTextFile(s + "/legs.csv", ReadTextFile(s + "/legs.csv") + "\n");
  };
  StatusOr<CalibrationReport> run = CalibrateSession({s}, hooks);
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.status().message().find("legs.csv changed while calibrating"), std::string::npos)
      << run.status().message();
  EXPECT_EQ(ReadTextFile(CalibrationReportPath(s)), report);
  // The results are whole but stale now, and say so.
  StatusOr<SessionResults> after = LoadSessionResults(s);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->changed_inputs, std::vector<std::string>{"legs.csv"});
  // A results/ mixed from two runs is refused by name.
  WriteTextFile(CalibrationReportPath(s), report + " ");
  StatusOr<SessionResults> mixed = LoadSessionResults(s);
  ASSERT_FALSE(mixed.ok());
  EXPECT_NE(mixed.status().message().find("report.json: does not match"), std::string::npos);
}

}  // namespace
}  // namespace hexcal::workflow

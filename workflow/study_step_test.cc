// `hexcal study` on a demo session of random poses (demo --random-poses
// --holdout 0): the measured poses are exactly those calibrate --session
// identified from; the selected subset's calibration beats the nominal robot
// on the poses it leaves out; the JSON is the same whatever the thread count;
// the figures are written, and not overwritten without force; bad requests
// are bad input.
#include "workflow/study_step.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/measurements.h"
#include "core/robot_io.h"
#include "core/validation.h"
#include "tests/test_support.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/study_options.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::TempDir;
using ::testing::HasSubstr;

constexpr int kPoses = 16;

class StudySession : public DemoSessionSuite<StudySession> {
 public:
  static DemoRequest Request() { return RandomPosesDemo(kPoses, /*seed=*/2); }

 protected:
  static void SetUpTestSuite() {
    DemoSessionSuite::SetUpTestSuite();
    // A failed demo has said why; Demo() would only throw.
    if (HasFatalFailure()) return;
    ASSERT_FALSE(Demo().calibration.validation.has_value());  // nothing held out
  }
  static StudyRequest SmallStudy() {
    StudyRequest request;
    request.session = Session();
    request.study.select = 8;
    request.study.subsets = 40;
    request.study.seed = 3;
    return request;
  }
};

// With nothing held out, calibrate --session --two-stage registered and
// mapped every image as the study does: results/calibration_measurements.csv
// holds the same rows (calibrate measured the images in memory, the study
// reads camera_poses.csv). The study calibrates its subsets two-stage.
TEST_F(StudySession, MeasuredPosesAreThoseCalibrateIdentifiedFrom) {
  CalibrateSessionRequest two_stage{Session()};
  two_stage.from_pixels.enabled = false;
  ASSERT_TRUE(CalibrateSession(two_stage).ok());
  StatusOr<MeasuredSession> session = LoadMeasuredSession(Session());
  ASSERT_TRUE(session.ok()) << session.status().message();
  StatusOr<std::vector<Measurement>> used = LoadMeasurements(Session() + "/results/calibration_measurements.csv");
  ASSERT_TRUE(used.ok()) << used.status().message();
  ASSERT_EQ(session->measurements.size(), used->size());
  ASSERT_EQ(session->images.size(), static_cast<size_t>(kPoses));
  for (size_t j = 0; j < used->size(); ++j) {
    // Equal up to the text round trip of the board poses through camera_poses.csv.
    EXPECT_LT((session->measurements[j].pose - (*used)[j].pose).cwiseAbs().maxCoeff(), 1e-7) << j;
    EXPECT_EQ(session->measurements[j].legs, (*used)[j].legs) << j;
    EXPECT_TRUE(session->measurements[j].pose_covariance.has_value());
  }
}

TEST_F(StudySession, SelectedCalibrationBeatsTheNominalRobotOnThePosesItLeavesOut) {
  StatusOr<StudyOutcome> study = RunStudy(SmallStudy());
  ASSERT_TRUE(study.ok()) << study.status().message();
  const SubsetOutcome& selected = study->result.selected;
  ASSERT_TRUE(selected.ok) << selected.failure;
  ASSERT_EQ(selected.poses.size(), 8u);

  StatusOr<MeasuredSession> session = LoadMeasuredSession(Session());
  ASSERT_TRUE(session.ok());
  std::vector<Measurement> held_out;
  for (int j = 0; j < kPoses; ++j) {
    if (!std::binary_search(selected.poses.begin(), selected.poses.end(), j))
      held_out.push_back(session->measurements[j]);
  }
  StatusOr<ValidationReport> nominal = Validate(session->nominal, held_out);
  ASSERT_TRUE(nominal.ok());
  EXPECT_LT(selected.heldout_position_rms, nominal->position.rms / 3);
  EXPECT_LT(selected.heldout_orientation_rms_deg, nominal->orientation_deg.rms);

  const nlohmann::json json = ToJson(*study);
  EXPECT_EQ(json["measured"], kPoses);
  EXPECT_EQ(json["random"]["count"], 40);
  EXPECT_EQ(json["random"]["failed"], 0);
  EXPECT_EQ(json["selected"]["images"].size(), 8u);
  const double percentile = json["selected"]["percentile"];
  EXPECT_GE(percentile, 0);
  EXPECT_LE(percentile, 100);
  EXPECT_EQ(json["selected"]["percentile"], json["selected"]["percentiles"]["heldout_position_rms"]);
  EXPECT_GT(json["selected"]["percentiles"]["O1"].get<double>(), 50);  // IOOPS on O1 beats most random subsets on O1
  const double median = json["random"]["heldout_position_rms"]["median"];
  EXPECT_GT(median, 0);
  EXPECT_THAT(FormatStudySummary(*study), HasSubstr("validates better than"));
}

TEST_F(StudySession, SameNumbersWhateverTheThreadsAndFiguresWritten) {
  TempDir dir;
  StudyRequest request = SmallStudy();
  request.study.num_threads = 1;
  StatusOr<StudyOutcome> one = RunStudy(request);
  request.study.num_threads = 2;
  request.plots = dir.File("plots");
  StatusOr<StudyOutcome> two = RunStudy(request);
  ASSERT_TRUE(one.ok() && two.ok());
  nlohmann::json a = ToJson(*one), b = ToJson(*two);
  for (nlohmann::json* j : {&a, &b}) {
    for (const char* key : {"seconds", "subsets_seconds", "threads", "figures", "created"}) j->erase(key);
  }
  EXPECT_EQ(a.dump(), b.dump());
  EXPECT_EQ(two->figures.size(), 12u);  // six histograms, SVG and PNG
  for (const char* stem : {"fig18_o1", "fig18_o4", "fig19_position", "fig19_orientation"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.File(std::string("plots/") + stem + ".svg"))) << stem;
  }
  StatusOr<StudyOutcome> again = RunStudy(request);  // without force
  ASSERT_FALSE(again.ok());
  EXPECT_THAT(again.status().message(), HasSubstr("--force"));
}

TEST_F(StudySession, BadRequestsAreBadInput) {
  StudyRequest request = SmallStudy();
  request.study.select = kPoses;
  StatusOr<StudyOutcome> study = RunStudy(request);
  ASSERT_FALSE(study.ok());
  EXPECT_EQ(study.status().kind(), StatusKind::kBadInput);
  EXPECT_THAT(study.status().message(), HasSubstr("the session has 16"));
  TempDir dir;
  request = SmallStudy();
  request.session = dir.File("nothing");
  study = RunStudy(request);
  ASSERT_FALSE(study.ok());
  EXPECT_THAT(study.status().message(), HasSubstr("session.yaml"));
}

// The option table makes the flags, the GUI form and the docs table: docs/cli.md
// carries the table it generates.
TEST(StudyOptions, SetTheRequestAndTheDocsListEveryOption) {
  StudyRequest request;
  ASSERT_TRUE(ApplyOptionEntries(StudyOptions(),
                                 {{"select", "9"},
                                  {"criterion", "O4"},
                                  {"secondary", "A"},
                                  {"unweighted_selection", "true"},
                                  {"seed", "7"},
                                  {"subsets", "50"}},
                                 &request, "study")
                  .ok());
  EXPECT_EQ(request.study.select, 9);
  EXPECT_EQ(request.study.criterion, Criterion::kO4);
  EXPECT_EQ(request.study.secondary, Criterion::kA);
  EXPECT_FALSE(request.weighted_selection);
  EXPECT_EQ(request.study.seed, 7u);
  EXPECT_EQ(request.study.subsets, 50);
  EXPECT_THAT(ApplyOptionEntries(StudyOptions(), {{"select", "6"}}, &request, "study").message(),
              HasSubstr("study.select: must be at least 7 poses, got 6"));
  // Issue 36: integers are read exactly, never rounded through a double.
  EXPECT_EQ(ApplyOptionEntries(StudyOptions(), {{"seed", "9007199254740993"}}, &request, "study").message(),
            "study.seed: must be at most 9007199254740992, got 9007199254740993");
  EXPECT_EQ(ApplyOptionEntries(StudyOptions(), {{"seed", "99999999999999999999"}}, &request, "study").message(),
            "study.seed: must be at most 9007199254740992, got 99999999999999999999");
  EXPECT_EQ(ApplyOptionEntries(StudyOptions(), {{"subsets", "1e3"}}, &request, "study").message(),
            "study.subsets: expected a whole number in decimal digits, got '1e3'");
  ASSERT_TRUE(ApplyOptionEntries(StudyOptions(), {{"seed", "9007199254740992"}}, &request, "study").ok());
  EXPECT_EQ(request.study.seed, 9007199254740992u);
  const std::string docs = hexcal::testing::ReadTextFile((hexcal::testing::SourceDir() / "docs" / "cli.md").string());
  const std::string table = OptionsMarkdownTable(StudyOptions());
  EXPECT_NE(docs.find(table), std::string::npos) << "docs/cli.md needs this table:\n" << table;
}

}  // namespace
}  // namespace hexcal::workflow

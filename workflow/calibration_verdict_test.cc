// The verdict (calibration_verdict.h): one test per level of each finding,
// from reports built here, and from demo sessions: a clean demo is good, a
// wrong reading and a noise model ten times too optimistic are not.
#include "report/calibration_verdict.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/csv.h"
#include "core/presets.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "report/expected_error.h"
#include "workflow/demo.h"
#include "workflow/session_calibrate.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kExpectedPosition = 0.005, kExpectedOrientation = 0.015;  // cm, degrees

// A report every check calls good: errors at the noise, s² = 1, σ below the
// noise, small changes, 24 + 8 images, nothing unusable or flagged.
CalibrationReport GoodReport() {
  CalibrationReport report;
  report.session = "run1";
  report.images = 32;
  report.calibration_images = 24;
  report.held_out_images = 8;
  report.length_unit = "cm";
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  EXPECT_TRUE(robot.ok());
  report.robot = *robot;
  report.noise = NoiseExpectation{NoiseModel{}, kExpectedPosition, kExpectedOrientation};
  report.closure_position_rms = 0.004;
  ValidationSummary validation;
  validation.rows = 8;
  validation.after = {0.0055, 0.01, 0.016, 0.03, 0};
  validation.per_image = {{"view_0030.png", 0.05, 0.004, 0.1, 0.01}, {"view_0031.png", 0.05, 0.009, 0.1, 0.02}};
  report.validation = validation;
  for (int leg = 1; leg <= 6; ++leg) {
    report.legs.push_back({leg, 1.0, 0.001, 5, "CONVERGENCE", 120.0});
    for (const char* name : {"ax", "ay", "az", "bx", "by", "bz", "l"})
      report.parameters.push_back({leg, name, 1.0, 1.02, 0.002});
  }
  return report;
}

const Finding& FindingOf(const Verdict& verdict, const std::string& aspect) {
  for (const Finding& f : verdict.findings)
    if (f.aspect == aspect) return f;
  ADD_FAILURE() << "no finding " << aspect;
  static const Finding none;
  return none;
}

VerdictLevel LevelOf(const CalibrationReport& report, const std::string& aspect) {
  return FindingOf(MakeVerdict(report), aspect).level;
}

TEST(Verdict, GoodReportIsGoodEverywhereWithoutAdvice) {
  const Verdict verdict = MakeVerdict(GoodReport());
  EXPECT_EQ(verdict.level, VerdictLevel::kGood);
  EXPECT_EQ(verdict.findings.size(), 9u);
  for (const Finding& f : verdict.findings) {
    EXPECT_EQ(f.level, VerdictLevel::kGood) << f.aspect << ": " << f.figure;
    EXPECT_TRUE(f.advice.empty()) << f.aspect;
    EXPECT_FALSE(f.meaning.empty()) << f.aspect;
  }
}

TEST(Verdict, LevelIsTheWorstFinding) {
  CalibrationReport report = GoodReport();
  report.unusable_images = 2;  // acceptable
  EXPECT_EQ(MakeVerdict(report).level, VerdictLevel::kAcceptable);
  report.calibration_images = 8;  // poor
  EXPECT_EQ(MakeVerdict(report).level, VerdictLevel::kPoor);
}

TEST(Verdict, HeldOutErrorAgainstTheNoisePrediction) {
  CalibrationReport report = GoodReport();
  report.validation->after.position_rms = 3 * kExpectedPosition;
  const Finding acceptable = FindingOf(MakeVerdict(report), "held-out error");
  EXPECT_EQ(acceptable.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(acceptable.figure, HasSubstr("= 3× expected 0.005 cm"));
  EXPECT_THAT(acceptable.advice, HasSubstr("view_0031.png"));  // the larger error
  report.validation->after.orientation_rms = 5 * kExpectedOrientation;
  EXPECT_EQ(LevelOf(report, "held-out error"), VerdictLevel::kPoor);
}

TEST(Verdict, NoHeldOutImagesOrFailedFkIsAcceptable) {
  CalibrationReport report = GoodReport();
  report.validation->after.failed = 1;
  EXPECT_EQ(LevelOf(report, "held-out error"), VerdictLevel::kAcceptable);
  report.validation.reset();
  const Finding finding = FindingOf(MakeVerdict(report), "held-out error");
  EXPECT_EQ(finding.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(finding.advice, HasSubstr("holdout"));
}

TEST(Verdict, ClosureAgainstTheNoisePrediction) {
  CalibrationReport report = GoodReport();
  report.closure_position_rms = 3 * kExpectedPosition;
  EXPECT_EQ(LevelOf(report, "closure"), VerdictLevel::kAcceptable);
  report.closure_position_rms = 10 * kExpectedPosition;
  const Finding poor = FindingOf(MakeVerdict(report), "closure");
  EXPECT_EQ(poor.level, VerdictLevel::kPoor);
  EXPECT_THAT(poor.advice, HasSubstr("recalibrate the camera"));
}

TEST(Verdict, ResidualsFarAboveOrBelowTheNoiseModel) {
  CalibrationReport report = GoodReport();
  report.legs[2].variance_factor = 9;  // s = 3
  const Finding above = FindingOf(MakeVerdict(report), "residuals");
  EXPECT_EQ(above.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(above.meaning, HasSubstr("leg 3"));
  report.legs[2].variance_factor = 25;  // s = 5
  EXPECT_EQ(LevelOf(report, "residuals"), VerdictLevel::kPoor);
  report.legs[2].variance_factor = 0.1;  // s = 0.32
  const Finding below = FindingOf(MakeVerdict(report), "residuals");
  EXPECT_EQ(below.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(below.meaning, HasSubstr("overstated"));
}

TEST(Verdict, ParameterSigmaAgainstTheNoisePrediction) {
  CalibrationReport report = GoodReport();
  report.parameters[10].sigma = 3 * kExpectedPosition;
  const Finding acceptable = FindingOf(MakeVerdict(report), "parameters (σ)");
  EXPECT_EQ(acceptable.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(acceptable.figure, HasSubstr("leg 2 bx"));
  report.parameters[10].sigma = 5 * kExpectedPosition;
  EXPECT_EQ(LevelOf(report, "parameters (σ)"), VerdictLevel::kPoor);
  report.parameters[10].sigma.reset();
  EXPECT_EQ(LevelOf(report, "parameters (σ)"), VerdictLevel::kPoor);
}

TEST(Verdict, LargeChangeOverSigmaIsNotAnAlarm) {
  CalibrationReport report = GoodReport();
  report.parameters[3].estimate = report.parameters[3].nominal + 0.1;  // 50σ, under 1 % of the size
  const Finding finding = FindingOf(MakeVerdict(report), "parameters (change)");
  EXPECT_EQ(finding.level, VerdictLevel::kGood);
  EXPECT_THAT(finding.meaning, HasSubstr("50 (leg 1 bx)"));
  EXPECT_THAT(finding.meaning, HasSubstr("not alarming"));
}

TEST(Verdict, ImplausibleChangesAgainstTheRobotSize) {
  CalibrationReport report = GoodReport();
  double size = 0;
  for (const Leg& leg : report.robot.legs) size = std::max(size, leg.a_in_base.head<2>().norm());
  report.parameters[5].estimate = report.parameters[5].nominal + 0.1 * size;
  EXPECT_EQ(LevelOf(report, "parameters (change)"), VerdictLevel::kAcceptable);
  report.parameters[5].estimate = report.parameters[5].nominal + 0.3 * size;
  const Finding poor = FindingOf(MakeVerdict(report), "parameters (change)");
  EXPECT_EQ(poor.level, VerdictLevel::kPoor);
  EXPECT_THAT(poor.advice, HasSubstr("nominal robot file"));
}

TEST(Verdict, TruthOnlyWhenKnown) {
  const CalibrationReport report = GoodReport();
  EXPECT_EQ(MakeVerdict(report).findings.size(), 9u);
  EXPECT_EQ(FindingOf(MakeVerdict(report, VerdictTruth{1.0, 42}), "parameters (truth)").level, VerdictLevel::kGood);
  EXPECT_EQ(FindingOf(MakeVerdict(report, VerdictTruth{0.8, 42}), "parameters (truth)").level,
            VerdictLevel::kAcceptable);
  EXPECT_EQ(FindingOf(MakeVerdict(report, VerdictTruth{0.5, 42}), "parameters (truth)").level, VerdictLevel::kPoor);
}

TEST(Verdict, ConditionNumber) {
  CalibrationReport report = GoodReport();
  report.legs[4].condition_number = 5e3;
  EXPECT_EQ(LevelOf(report, "identifiability"), VerdictLevel::kAcceptable);
  report.legs[4].condition_number = 1e5;
  const Finding poor = FindingOf(MakeVerdict(report), "identifiability");
  EXPECT_EQ(poor.level, VerdictLevel::kPoor);
  EXPECT_THAT(poor.figure, HasSubstr(", leg 5"));
  for (LegFit& leg : report.legs) leg.condition_number.reset();  // an older report: no finding
  for (const Finding& f : MakeVerdict(report).findings) EXPECT_NE(f.aspect, "identifiability");
}

TEST(Verdict, TooFewPoses) {
  CalibrationReport report = GoodReport();
  report.held_out_images = 3;
  EXPECT_EQ(LevelOf(report, "poses"), VerdictLevel::kAcceptable);
  report.held_out_images = 8;
  report.calibration_images = 15;
  const Finding acceptable = FindingOf(MakeVerdict(report), "poses");
  EXPECT_EQ(acceptable.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(acceptable.advice, HasSubstr("at least 6 more"));
  report.calibration_images = 9;
  EXPECT_EQ(LevelOf(report, "poses"), VerdictLevel::kPoor);
}

TEST(Verdict, UnusableImages) {
  CalibrationReport report = GoodReport();
  report.unusable_images = 4;
  EXPECT_EQ(LevelOf(report, "unusable images"), VerdictLevel::kAcceptable);
  report.unusable_images = 12;
  EXPECT_EQ(LevelOf(report, "unusable images"), VerdictLevel::kPoor);
}

TEST(Verdict, OutliersNameTheImagesLeftOutAndTheirCause) {
  CalibrationReport report = GoodReport();
  report.calibration_images = 40;
  // One image with a wrong reading, one whose board pose disagrees with 5 legs: 2 of 40 left out.
  report.outliers = {{"view_0003.png", 5, 2, 0.01, 6.2, true}};
  for (int leg = 1; leg <= 5; ++leg) report.outliers.push_back({"view_0007.png", 9, leg, 3.4, -4800, true});
  const Finding good = FindingOf(MakeVerdict(report), "outliers");
  EXPECT_EQ(good.level, VerdictLevel::kGood);
  EXPECT_THAT(good.figure, HasSubstr("2 calibration images of 40 left out for 6 flagged readings: view_0003.png "
                                     "(legs.csv line 5), a wrong reading on leg 2; view_0007.png (legs.csv line 9), "
                                     "a swapped or mislabelled image?"));
  EXPECT_THAT(good.meaning, HasSubstr("its board pose disagrees with 5 of 6 legs"));
  report.calibration_images = 20;  // 10 %
  EXPECT_EQ(LevelOf(report, "outliers"), VerdictLevel::kAcceptable);
  report.calibration_images = 10;  // 20 %
  const Finding poor = FindingOf(MakeVerdict(report), "outliers");
  EXPECT_EQ(poor.level, VerdictLevel::kPoor);
  EXPECT_THAT(poor.advice, HasSubstr("check that images and legs.csv rows belong together"));
}

// A points session's rows are poses measured by the tracker: its findings say so.
TEST(Verdict, APointsSessionsFindingsCountPosesNotImages) {
  CalibrationReport report = GoodReport();
  report.instrument = Instrument::kPoints;
  report.calibration_images = 24;
  report.held_out_images = 3;
  const Finding poses = FindingOf(MakeVerdict(report), "poses");
  EXPECT_THAT(poses.figure, HasSubstr("24 calibration poses, 3 held out"));
  EXPECT_THAT(poses.threshold, HasSubstr("calibration poses, 3 per leg parameter"));
  EXPECT_THAT(poses.advice, HasSubstr("poses (holdout = 1 in legs.csv)"));
  EXPECT_EQ(FindingOf(MakeVerdict(report), "outliers").figure, "no reading flagged (24 calibration poses)");
  EXPECT_THAT(FindingOf(MakeVerdict(report), "closure").meaning, HasSubstr("tracker, registered frames"));
  report.outliers = {{"pose_0003", 5, 2, 0.01, 6.2, false}};
  const Finding kept = FindingOf(MakeVerdict(report), "outliers");
  EXPECT_THAT(kept.meaning, HasSubstr("disagree with the tracker"));
  EXPECT_THAT(kept.advice, HasSubstr("check the readings of pose pose_0003 (legs.csv line 5)"));
}

TEST(Verdict, OutliersKeptInTheFitNameTheWorstReading) {
  CalibrationReport report = GoodReport();
  report.outliers = {{"view_0003.png", 5, 2, 0.01, 6.2, false}, {"view_0007.png", 9, 3, 0.1, -48, false}};
  const Finding acceptable = FindingOf(MakeVerdict(report), "outliers");
  EXPECT_EQ(acceptable.level, VerdictLevel::kAcceptable);
  EXPECT_EQ(acceptable.advice,
            "check the readings of image view_0007.png (legs.csv line 9), leg 3: its residual is 48σ; without "
            "--keep-outliers it is left out");
  for (int j = 0; j < 10; ++j) report.outliers.push_back({"view_0010.png", 12, 1 + j % 6, 0.01, 6, false});
  EXPECT_EQ(LevelOf(report, "outliers"), VerdictLevel::kPoor);
}

TEST(Verdict, AFocalErrorIsNamedAsSuchNotTheRobotFile) {
  CalibrationReport report = GoodReport();
  report.from_pixels = PixelFitSummary{};
  report.from_pixels->estimated = {{"fx", 948.36, 903.167, 0.041}, {"fy", 948.36, 903.167, 0.041}};
  const Finding camera = FindingOf(MakeVerdict(report), "camera (scale)");
  EXPECT_EQ(camera.level, VerdictLevel::kAcceptable);
  EXPECT_THAT(camera.figure, HasSubstr("largest change 4.77 % (fx 948 -> 903"));
  EXPECT_THAT(camera.meaning, HasSubstr("the camera file's fx is 5 % off"));
  EXPECT_THAT(camera.advice, HasSubstr("recalibrate the camera"));
  for (ParameterEstimate& p : report.parameters)
    if (p.name == "az") p.estimate = p.nominal + 3.5;  // the frames' shift the focal error caused
  const Finding change = FindingOf(MakeVerdict(report), "parameters (change)");
  EXPECT_EQ(change.level, VerdictLevel::kPoor);
  EXPECT_THAT(change.advice, HasSubstr("recalibrate the camera (hexcal intrinsics)"));
  report.from_pixels->estimated = {{"fx", 903.2, 903.167, 0.041}, {"target_scale", 1, 1.0004, 0.0002}};
  EXPECT_EQ(LevelOf(report, "camera (scale)"), VerdictLevel::kGood);
  EXPECT_THAT(FindingOf(MakeVerdict(report), "parameters (change)").advice, HasSubstr("check the nominal robot file"));
}

TEST(Verdict, TextAndJsonForms) {
  CalibrationReport report = GoodReport();
  report.unusable_images = 2;
  const Verdict verdict = MakeVerdict(report);
  const std::string text = verdict.ToText();
  EXPECT_THAT(text, StartsWith("Verdict: acceptable\n"));
  EXPECT_THAT(text, HasSubstr("\n  acceptable unusable images: 2 of 32 images without a usable board pose (good: "));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + static_cast<long>(verdict.findings.size()));
  const nlohmann::json json = verdict.ToJson();
  EXPECT_EQ(json["level"], "acceptable");
  ASSERT_EQ(json["findings"].size(), verdict.findings.size());
  EXPECT_EQ(json["findings"][0]["aspect"], "held-out error");
  EXPECT_TRUE(json["findings"][0]["advice"].is_null());
  for (const char* key : {"level", "figure", "threshold", "meaning"}) EXPECT_TRUE(json["findings"][0].contains(key));
}

TEST(Verdict, ValidationOfAFileAgainstTheNoisePrediction) {
  ValidationReport report;
  report.position.rms = 0.004;
  report.orientation_deg.rms = 0.01;
  const ExpectedPoseError expected{kExpectedPosition, kExpectedOrientation};
  const Verdict good = MakeValidationVerdict(report, expected, "cm");
  ASSERT_EQ(good.findings.size(), 1u);
  EXPECT_EQ(good.findings[0].aspect, "FK error");
  EXPECT_EQ(good.level, VerdictLevel::kGood);
  report.position.rms = 10 * kExpectedPosition;
  const Verdict poor = MakeValidationVerdict(report, expected, "cm");
  EXPECT_EQ(poor.level, VerdictLevel::kPoor);
  EXPECT_THAT(poor.findings[0].advice, HasSubstr("--noise-*"));
}

TEST(ExpectedError, PoseNoiseAloneAndWithReadings) {
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  ASSERT_TRUE(robot.ok());
  const Pose pose = robot->PoseFromVector((Vector6d() << 0, 0, 55, 0, 0, 0).finished());
  NoiseModel noise{0.003, 0.03, 0};
  const ExpectedPoseError pose_only = ExpectedFkError(*robot, pose, noise);
  EXPECT_NEAR(pose_only.position_rms, std::sqrt(3.0) * noise.PositionStdDev(), 1e-12);
  EXPECT_NEAR(pose_only.orientation_rms_deg, std::sqrt(3.0) * RadToDeg(noise.AngleStdDevRad()), 1e-12);
  noise.leg = 0.003;
  const ExpectedPoseError with_legs = ExpectedFkError(*robot, std::vector<Pose>{pose, pose}, noise);
  EXPECT_GT(with_legs.position_rms, pose_only.position_rms * 1.2);
  EXPECT_GT(with_legs.orientation_rms_deg, pose_only.orientation_rms_deg);
}

// The demo session of `hexcal demo` (24 planned, 8 held out), then edited.
class DemoVerdict : public DemoSessionSuite<DemoVerdict> {
 public:
  static DemoRequest Request() { return DemoRequest{}; }
};

TEST_F(DemoVerdict, CleanDemoIsGood) {
  EXPECT_EQ(Demo().verdict.level, VerdictLevel::kGood) << Demo().verdict.ToText();
  EXPECT_EQ(FindingOf(Demo().verdict, "parameters (truth)").level, VerdictLevel::kGood);
  // The report on disk carries what the verdict needs.
  StatusOr<CalibrationReport> saved = LoadCalibrationReport(CalibrationReportPath(Session()));
  ASSERT_TRUE(saved.ok()) << saved.status().message();
  ASSERT_TRUE(saved->noise.has_value());
  EXPECT_EQ(MakeVerdict(*saved).ToText(), MakeVerdict(Demo().calibration).ToText());
}

// Adds `delta` (robot unit) to leg 3's reading of the first calibration row.
void SpoilReading(const std::string& session, double delta) {
  const std::string legs = SessionPaths(session).legs;
  StatusOr<CsvTable> table = ReadCsv(legs);
  ASSERT_TRUE(table.ok()) << table.status().message();
  const auto column = [&](const std::string& name) {
    return std::find(table->header.begin(), table->header.end(), name) - table->header.begin();
  };
  for (std::vector<std::string>& row : table->rows) {
    if (row[column("holdout")] == "1") continue;
    row[column("L3")] = FormatNumber(std::stod(row[column("L3")]) + delta);
    break;
  }
  ASSERT_TRUE(WriteCsv(legs, table->header, table->rows).ok());
}

TEST_F(DemoVerdict, WrongReadingAndOptimisticNoiseAreFlagged) {
  SpoilReading(Session(), 0.1);  // 1 mm on a cm robot: hundreds of σ
  StatusOr<CalibrationReport> spoilt = CalibrateSession({Session()});
  ASSERT_TRUE(spoilt.ok()) << spoilt.status().message();
  // One of the demo's 24 calibration images left out, named: good on the rest.
  const Finding outliers = FindingOf(MakeVerdict(*spoilt), "outliers");
  EXPECT_EQ(outliers.level, VerdictLevel::kGood);
  EXPECT_THAT(outliers.figure, HasSubstr("a wrong reading on leg 3"));

  StatusOr<SessionConfig> config = LoadSessionConfig(Session());
  ASSERT_TRUE(config.ok());
  config->noise.position /= 10;
  config->noise.angle_deg /= 10;
  config->noise.leg /= 10;
  ASSERT_TRUE(SaveSessionConfig(Session(), *config).ok());
  StatusOr<CalibrationReport> optimistic = CalibrateSession({Session()});
  ASSERT_TRUE(optimistic.ok()) << optimistic.status().message();
  const Verdict verdict = MakeVerdict(*optimistic);
  EXPECT_EQ(verdict.level, VerdictLevel::kPoor) << verdict.ToText();
  EXPECT_EQ(FindingOf(verdict, "held-out error").level, VerdictLevel::kPoor);
}

}  // namespace
}  // namespace hexcal::workflow

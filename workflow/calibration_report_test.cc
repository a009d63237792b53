#include "session/calibration_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/calibration.h"
#include "core/presets.h"
#include "core/robot_io.h"
#include "session/json_fields.h"
#include "tests/test_support.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::ReadTextFile;
using hexcal::testing::SourceDir;
using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;
using ::testing::Not;

CalibrationReport SampleReport() {
  CalibrationReport report;
  report.session = "run1";
  report.images = 10;
  report.unusable_images = 1;
  report.calibration_images = 7;
  report.held_out_images = 2;
  report.length_unit = "cm";
  report.registration.position_rms = 0.15;
  report.registration.base_from_camera << 1, 2, 3, 4, 5, 6;
  report.registration.platform_from_target << -1, -2, -3, 0.5, 0, 90;
  report.closure_position_rms = 0.004;
  report.closure_angle_rms_deg = 0.02;
  ValidationSummary validation;
  validation.rows = 2;
  validation.before = {0.04, 0.05, 0.2, 0.3, 0};
  validation.after = {0.004, 0.005, 0.01, 0.02, 1};
  validation.per_image = {{"a.png", 0.03, 0.003, 0.1, 0.01}, {"b.png", 0.05, std::nullopt, 0.2, std::nullopt}};
  report.validation = validation;
  report.calibrated_robot = "run1/results/calibrated.yaml";
  report.robot = *LoadRobot("inria-left-hand");
  for (int k = 0; k < kNumParams; ++k)
    report.parameters.push_back({k / 7 + 1, ParameterName(k % 7), 1.0 * k, 1.0 * k + 0.01,
                                 k % 5 == 0 ? std::nullopt : std::optional<double>(0.001 * k)});
  for (int i = 1; i <= 6; ++i) report.legs.push_back({i, 1.1, 0.001, 5, "CONVERGENCE"});
  return report;
}

TEST(CalibrationReport, JsonRoundTripIsExact) {
  const CalibrationReport report = SampleReport();
  const nlohmann::json json = ToJson(report);
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(ToJson(*read), json);
  EXPECT_EQ(read->validation->per_image[1].position_after, std::nullopt);
  EXPECT_EQ(read->parameters[0].sigma, std::nullopt);
  EXPECT_DOUBLE_EQ(*read->parameters[1].sigma, 0.001);
}

TEST(CalibrationReport, WithoutValidationRoundTrips) {
  CalibrationReport report = SampleReport();
  report.validation.reset();
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(ToJson(report), "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_FALSE(read->validation.has_value());
}

CalibrationReport ReportWithOutliers(bool keep) {
  CalibrationReport report = SampleReport();
  report.screening = OutlierScreeningSummary{5, keep, true};
  report.outliers = {{"img_007.png", 9, 3, 1.0024, 48.12, !keep},
                     {"img_011.png", std::nullopt, 6, -0.25, -12.5, !keep}};
  return report;
}

TEST(CalibrationReport, OutliersRoundTrip) {
  const nlohmann::json json = ToJson(ReportWithOutliers(false));
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(ToJson(*read), json);
  ASSERT_EQ(read->outliers.size(), 2u);
  EXPECT_EQ(read->outliers[0].legs_line, 9);
  EXPECT_EQ(read->outliers[1].legs_line, std::nullopt);
  EXPECT_TRUE(read->outliers[0].excluded);
  ASSERT_TRUE(read->screening.has_value());
  EXPECT_EQ(read->screening->threshold, 5);
}

// Reports written before the screening have neither key and still load.
TEST(CalibrationReport, ReportsWithoutOutlierKeysLoad) {
  nlohmann::json json = ToJson(SampleReport());
  json.erase("outliers");
  json.erase("outlier_screening");
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_TRUE(read->outliers.empty());
  EXPECT_FALSE(read->screening.has_value());
}

CalibrationReport ReportWithCameraFrameResiduals(bool signatures) {
  CalibrationReport report = SampleReport();
  report.images = 27;
  report.calibration_images = 24;
  CameraFrameResiduals r;
  r.images = 24;
  r.fk_failed = 1;
  r.depth_min = 66.5;
  r.depth_max = 71.25;
  r.axes[0] = {0.00003, 0.003, 0.0011, 0.027, 0.0001, 0.0004, -0.00002, 0.0003};
  r.axes[1] = {-0.0002, 0.0025, 0.00094, -0.21, -0.0002, 0.0004, 0.00005, 0.0003};
  r.axes[2] = {0.0123, 0.0024, 0.0009, 13.7, -0.0049, 0.0004, -0.0049, 0.0004};
  if (signatures) r.signatures = BiasSignatures{{-0.78, 0.02, -0.03}, {-0.8, -0.25, -0.2}};
  report.camera_frame_residuals = r;
  return report;
}

TEST(CalibrationReport, CameraFrameResidualsRoundTrip) {
  for (bool signatures : {false, true}) {
    const nlohmann::json json = ToJson(ReportWithCameraFrameResiduals(signatures));
    StatusOr<CalibrationReport> read = CalibrationReportFromJson(json, "report.json");
    ASSERT_TRUE(read.ok()) << read.status().message();
    EXPECT_EQ(ToJson(*read), json);
    ASSERT_TRUE(read->camera_frame_residuals.has_value());
    const CameraFrameResiduals& r = *read->camera_frame_residuals;
    EXPECT_EQ(r.images, 24);
    EXPECT_EQ(r.fk_failed, 1);
    EXPECT_EQ(r.depth_max, 71.25);
    EXPECT_EQ(r.axes[2].t, 13.7);
    EXPECT_EQ(r.axes[1].scale_slope, 0.00005);
    EXPECT_EQ(r.signatures.has_value(), signatures);
    if (signatures) {
      EXPECT_EQ(r.signatures->target_scale.y_slope, -0.2);
    }
    EXPECT_EQ(json["camera_frame_residuals"]["axes"]["z"]["std"], 0.0024);
    EXPECT_THAT(json["camera_frame_residuals"]["finding"].get<std::string>(),
                HasSubstr("a bias along the optical axis; points to the focal length"));
  }
}

// Reports written before the diagnosis have no key (and a null one reads as none).
TEST(CalibrationReport, ReportsWithoutCameraFrameResidualsLoad) {
  nlohmann::json json = ToJson(SampleReport());
  EXPECT_TRUE(json["camera_frame_residuals"].is_null());
  StatusOr<CalibrationReport> null_key = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(null_key.ok()) << null_key.status().message();
  EXPECT_FALSE(null_key->camera_frame_residuals.has_value());
  json.erase("camera_frame_residuals");
  StatusOr<CalibrationReport> old = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(old.ok()) << old.status().message();
  EXPECT_FALSE(old->camera_frame_residuals.has_value());
  EXPECT_THAT(FormatCalibrationSummary(*old), Not(HasSubstr("camera-frame residuals")));
}

TEST(CalibrationReport, SummaryHasTheCameraFrameLine) {
  EXPECT_THAT(FormatCalibrationSummary(ReportWithCameraFrameResiduals(false)),
              HasSubstr("\ncamera-frame residuals (cm, 24 images, mean ± standard error; robot − camera): x +0.0000 ± "
                        "0.0011, y -0.00020 ± 0.00094, z +0.01230 ± 0.00090 (t = +13.7, depth slope -0.490 % ± "
                        "0.040 %): a bias along the optical axis; points to the focal length (camera depths about "
                        "0.49 % too long)\n"));
}

TEST(CalibrationReport, SummaryNamesEachOutlier) {
  const std::string excluded = FormatCalibrationSummary(ReportWithOutliers(false));
  EXPECT_THAT(excluded, HasSubstr("outlier: img_007.png (legs.csv line 9) leg 3: residual 1.002 cm = 48.12 sigma; "
                                  "excluded from leg 3's fit (--keep-outliers keeps it)\n"));
  EXPECT_THAT(excluded, HasSubstr("outlier: img_011.png leg 6: residual -0.25 cm = -12.5 sigma; excluded"));
  EXPECT_THAT(excluded, HasSubstr("registration (nominal robot, without the 2 images holding an outlier)"));
  const std::string kept = FormatCalibrationSummary(ReportWithOutliers(true));
  EXPECT_THAT(kept, HasSubstr("leg 3: residual 1.002 cm = 48.12 sigma; kept in leg 3's fit (--keep-outliers)\n"));
  EXPECT_THAT(kept, HasSubstr("registration (nominal robot): closure"));
  CalibrationReport few = SampleReport();
  few.screening = OutlierScreeningSummary{5, false, false};
  EXPECT_THAT(FormatCalibrationSummary(few), HasSubstr("note: 7 calibration images are too few to screen"));
}

CalibrationReport ReportWithImageClosures() {
  CalibrationReport report = ReportWithOutliers(false);
  report.closure_position_rms = 0.004;
  report.closure_by_image = {{"img_003.png", 5, true, 0.006, 0.01, false, {}},
                             {"img_007.png", 9, true, 8.5, 12.5, true, {1, 2, 3, 4, 5}},
                             {"img_011.png", std::nullopt, false, 0, 0, true, {6}}};
  return report;
}

TEST(CalibrationReport, ImageClosuresRoundTripAndNameTheLeftOutImages) {
  const nlohmann::json json = ToJson(ReportWithImageClosures());
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(json, "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(ToJson(*read), json);
  ASSERT_EQ(read->closure_by_image.size(), 3u);
  EXPECT_EQ(read->closure_by_image[1].excluded_legs, (std::vector<int>{1, 2, 3, 4, 5}));
  const std::string text = FormatCalibrationSummary(*read);
  EXPECT_THAT(text, HasSubstr("left out: img_007.png (legs.csv line 9), closure 8.5 cm, 12.5 deg: its board pose "
                              "disagrees with 5 of 6 legs: a swapped or mislabelled image?"));
  EXPECT_THAT(text, HasSubstr("left out: img_011.png, closure unknown (FK did not converge): a wrong reading on leg 6"));
  EXPECT_THAT(text, HasSubstr("closure by image: worst img_003.png (legs.csv line 5) 0.006 cm, 0.01 deg (1.5× the RMS)"));
  nlohmann::json old = json;  // reports that predate it
  old["closure_after_calibration"].erase("by_image");
  read = CalibrationReportFromJson(old, "report.json");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_TRUE(read->closure_by_image.empty());
}

std::string ErrorOf(const std::string& text) {
  StatusOr<nlohmann::json> json = ParseJsonText(text, "r.json");
  if (!json.ok()) return json.status().message();
  StatusOr<CalibrationReport> read = CalibrationReportFromJson(*json, "r.json");
  EXPECT_FALSE(read.ok());
  return read.ok() ? "" : read.status().message();
}

// Wrong documents are refused with the key and the problem, never an abort.
TEST(CalibrationReport, WrongDocumentsNameTheKey) {
  EXPECT_THAT(ErrorOf("{}"), HasSubstr("r.json: key 'session': missing (expected a string)"));
  EXPECT_THAT(ErrorOf("[]"), HasSubstr("r.json: expected a JSON object"));
  EXPECT_THAT(ErrorOf("null"), HasSubstr("expected a JSON object"));
  EXPECT_THAT(ErrorOf("not json"), HasSubstr("r.json: not valid JSON"));
  nlohmann::json json = ToJson(SampleReport());
  json["images"] = "ten";
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'images': expected a whole number"));
  json = ToJson(SampleReport());
  json["registration"]["base_from_camera"] = {1, 2};
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'registration.base_from_camera': expected a list of 6 numbers"));
  json = ToJson(SampleReport());
  json["parameters"][3]["estimate"] = "x";
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'parameters[3].estimate': expected a finite number"));
  json = ToJson(SampleReport());
  json["parameters"].erase(0);
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'parameters': expected 42 parameters"));
  json = ToJson(SampleReport());
  json["validation"]["per_image"] = 5;
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'validation.per_image': expected a list"));
  json = ToJson(ReportWithOutliers(false));
  json["outliers"][1]["excluded"] = "yes";
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'outliers[1].excluded': expected true or false"));
  json = ToJson(ReportWithCameraFrameResiduals(true));
  json["camera_frame_residuals"]["axes"]["z"]["t"] = "x";
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'camera_frame_residuals.axes.z.t': expected a finite number"));
  json = ToJson(ReportWithCameraFrameResiduals(true));
  json["camera_frame_residuals"]["signatures"].erase("focal_length");
  EXPECT_THAT(ErrorOf(json.dump()), HasSubstr("key 'camera_frame_residuals.signatures.focal_length': missing"));
}

TEST(CalibrationReport, SaveAndLoad) {
  TempDir dir;
  const std::string path = dir.File("report.json");
  ASSERT_TRUE(SaveCalibrationReport(path, SampleReport()).ok());
  StatusOr<CalibrationReport> read = LoadCalibrationReport(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(ToJson(*read), ToJson(SampleReport()));
  EXPECT_THAT(LoadCalibrationReport(dir.File("none.json")).status().message(), HasSubstr("no such file"));
}

}  // namespace
}  // namespace hexcal::workflow

// The result of a session calibration (`hexcal calibrate --session`, the
// GUI's Calibrate step), as one typed value: what results/report.json holds.
// Written by CalibrateSession, read back by the HTML report, the demo and the
// GUI panels through CalibrationReportFromJson, which names the key and the
// problem of a wrong file instead of aborting (docs/session.md has the keys).
//
//   StatusOr<CalibrationReport> report = LoadCalibrationReport("run1/results/report.json");
//   if (report.ok() && report->validation) Print(report->validation->after.position_rms);
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera_frame_residuals.h"
#include "core/noise_model.h"
#include "core/robot.h"
#include "core/session.h"
#include "core/status.h"
#include "session/image_closure.h"
#include "session/pixel_fit_summary.h"
#include "session/point_fit_summary.h"

namespace hexcal::workflow {

struct PoseErrorStats {
  double position_rms = 0, position_max = 0;        // robot unit
  double orientation_rms = 0, orientation_max = 0;  // degrees
  int failed = 0;                                   // rows whose FK did not converge
};

struct HeldOutImage {
  std::string image;
  // Empty where FK did not converge for that robot.
  std::optional<double> position_before, position_after;        // robot unit
  std::optional<double> orientation_before, orientation_after;  // degrees
};

struct ValidationSummary {
  int rows = 0;
  PoseErrorStats before, after;  // nominal robot, calibrated robot
  std::vector<HeldOutImage> per_image;
};

struct RegistrationSummary {
  // Closure |A·Y − X·B| with the nominal robot (registration.h).
  double position_rms = 0, angle_rms_deg = 0, position_max = 0, angle_max_deg = 0;
  Vector6d base_from_camera = Vector6d::Zero();      // x y z (robot unit) and Euler xyz (deg)
  Vector6d platform_from_target = Vector6d::Zero();  // the same
};

struct ParameterEstimate {
  int leg = 0;       // 1..6
  std::string name;  // ax, ay, az, bx, by, bz, l
  double nominal = 0, estimate = 0;
  std::optional<double> sigma;  // robot unit; none when the leg has no uncertainty
};

struct LegFit {
  int leg = 0;
  double variance_factor = 0, residual_rms = 0;
  int iterations = 0;
  std::string termination;
  // σ_max/σ_min of the leg's weighted identification Jacobian at the
  // estimate; none in reports older than the verdict (calibration_verdict.h).
  std::optional<double> condition_number = std::nullopt;
};

// A leg reading that failed the outlier screening (core/outlier_screening.h).
struct OutlierReading {
  std::string image;             // legs.csv's image name
  std::optional<int> legs_line;  // its line in legs.csv, when known
  int leg = 0;                   // 1..6
  double residual = 0;           // reading − what the camera pose implies, robot unit
  double z = 0;                  // the same in standard deviations of the noise model
  bool excluded = false;         // left out of that leg's fit (false with --keep-outliers)
};

// How the readings were screened; absent from reports older than the screening.
struct OutlierScreeningSummary {
  double threshold = 0;   // |z| bound
  bool keep = false;      // --keep-outliers
  bool screened = false;  // false: too few calibration images (kMinRowsToScreen)
};

// The noise model the calibration assumed (session.yaml's `noise:`) and the
// FK error it predicts on the held-out poses (expected_error.h); none in
// reports older than the verdict (calibration_verdict.h).
struct NoiseExpectation {
  NoiseModel model;                // half-widths, robot unit and degrees
  double position_rms = 0;         // robot unit
  double orientation_rms_deg = 0;  // degrees
};

struct CalibrationReport {
  std::string session;
  // What measured the poses (core/session.h): the camera, or points (a laser
  // tracker's; then "images" below count poses). In report.json only for points.
  Instrument instrument = Instrument::kCamera;
  int images = 0, unusable_images = 0, calibration_images = 0, held_out_images = 0;
  std::string length_unit;
  RegistrationSummary registration;
  double closure_position_rms = 0, closure_angle_rms_deg = 0;  // with the calibrated robot
  // Each calibration image's closure (image_closure.h); empty in reports that predate it.
  std::vector<ImageClosure> closure_by_image;
  std::optional<ValidationSummary> validation;                 // none without held-out images
  std::string calibrated_robot;                                // path of results/calibrated.yaml
  Robot robot;                                                 // the calibrated robot (legs only)
  std::vector<ParameterEstimate> parameters;                   // 42, leg by leg
  std::vector<LegFit> legs;                                    // 6
  std::optional<OutlierScreeningSummary> screening;            // none in reports that predate it
  std::vector<OutlierReading> outliers;                        // by image, then leg
  std::optional<NoiseExpectation> noise;                       // none in reports that predate it
  // The calibration from pixels (pixel_fit_summary.h); none for the two-stage one.
  std::optional<PixelFitSummary> from_pixels;
  // The calibration from points (point_fit_summary.h); none for the two-stage one.
  std::optional<PointFitSummary> from_points;
  // FK of the calibrated robot against the camera, in the camera frame, over
  // the calibration images (docs/calibration.md, "Bias along the optical
  // axis"); none in reports that predate it or when it could not be computed.
  std::optional<CameraFrameResiduals> camera_frame_residuals;

  int usable_images() const { return images - unusable_images; }
};

nlohmann::json ToJson(const CalibrationReport& report);
// `source` names the document in errors (its path).
StatusOr<CalibrationReport> CalibrationReportFromJson(const nlohmann::json& json, const std::string& source);

// results/report.json of a session folder.
std::string CalibrationReportPath(const std::string& session_dir);
StatusOr<CalibrationReport> LoadCalibrationReport(const std::string& path);
Status SaveCalibrationReport(const std::string& path, const CalibrationReport& report);

}  // namespace hexcal::workflow

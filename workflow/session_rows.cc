#include "workflow/session_rows.h"

#include <algorithm>
#include <filesystem>

#include "core/calibration.h"
#include "core/csv.h"
#include "core/forward_kinematics.h"
#include "report/expected_error.h"
#include "session/results_files.h"

namespace hexcal::workflow {
namespace {

PoseErrorStats StatsOf(const ValidationReport& report) {
  return {report.position.rms, report.position.max, report.orientation_deg.rms, report.orientation_deg.max,
          report.failed};
}

std::optional<double> IfOk(bool ok, double value) { return ok ? std::optional<double>(value) : std::nullopt; }

void FillParameters(const CalibrationResult& calibration, CalibrationReport* report) {
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = calibration.legs[i];
    for (int k = 0; k < kParamsPerLeg; ++k) {
      report->parameters.push_back({i + 1, ParameterName(k), leg.initial[k], leg.estimate[k],
                                    leg.has_uncertainty ? std::optional<double>(leg.std_dev[k]) : std::nullopt});
    }
    const LegParameters& singular = leg.singular_values;  // descending
    const std::optional<double> condition = leg.has_uncertainty && singular[kParamsPerLeg - 1] > 0
                                                ? std::optional<double>(singular[0] / singular[kParamsPerLeg - 1])
                                                : std::nullopt;
    report->legs.push_back(
        {i + 1, leg.variance_factor, leg.residual_rms, leg.iterations, leg.termination, condition});
  }
}

// The screened-out readings by image (legs.csv order), then leg.
std::vector<OutlierReading> OutlierReadings(const CalibrationResult& calibration, const SplitRows& split) {
  std::vector<OutlierReading> outliers;
  for (int i = 0; i < kNumLegs; ++i) {
    for (const RowOutlier& o : calibration.legs[i].outliers) {
      const LegsRow& row = *split.calibration_rows[o.measurement];
      const std::optional<int> line = row.line > 0 ? std::optional<int>(row.line) : std::nullopt;
      outliers.push_back({row.image, line, i + 1, o.residual, o.z, o.excluded});
    }
  }
  std::stable_sort(outliers.begin(), outliers.end(), [](const OutlierReading& a, const OutlierReading& b) {
    return a.legs_line.value_or(0) < b.legs_line.value_or(0);
  });
  return outliers;
}

}  // namespace

std::string RowName(const LegsRow& row) { return row.image + " (legs.csv line " + std::to_string(row.line) + ")"; }

Status CheckRowsNearStroke(const Robot& nominal, const std::vector<LegsRow>& rows) {
  const std::string unit = LengthUnitName(nominal.length_unit);
  for (const LegsRow& row : rows) {
    for (int i = 0; i < kNumLegs; ++i) {
      const Leg& leg = nominal.legs[i];
      const double span = leg.stroke_max - leg.stroke_min;
      if (row.legs[i] >= leg.stroke_min - span && row.legs[i] <= leg.stroke_max + span) continue;
      return Status::BadInput(RowName(row) + ": L" + std::to_string(i + 1) + " = " + FormatNumber(row.legs[i]) + " " +
                              unit + " is far outside leg " + std::to_string(i + 1) + "'s stroke [" +
                              FormatNumber(leg.stroke_min) + ", " + FormatNumber(leg.stroke_max) + "] " + unit +
                              ": a typo, or a reading in another unit? Fix the reading");
    }
  }
  return Status::Ok();
}

Status CheckNominalFk(const Robot& nominal, const Pose& start, const std::vector<const LegsRow*>& rows) {
  for (const LegsRow* row : rows) {
    StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(nominal, row->legs, start);
    if (fk.ok()) continue;
    std::string legs;
    for (int i = 0; i < kNumLegs; ++i) legs += (i ? ", " : "") + FormatSignificant(row->legs[i], 6);
    return Status::Failed(RowName(*row) + ": " + fk.status().message() + "; its readings L1..L6 = " + legs + " " +
                          LengthUnitName(nominal.length_unit) +
                          " fit no pose of the nominal robot: check them (a typo, another image's readings?)");
  }
  return Status::Ok();
}

// Held-out rows: the camera pose mapped into the registered base frame.
std::vector<Measurement> HeldOutMeasurements(const SessionInputs& in, const CameraPoses& poses,
                                             const std::vector<const LegsRow*>& held_out,
                                             const CameraCalibrationResult& result, double scale) {
  std::vector<Measurement> rows;
  for (const LegsRow* row : held_out) {
    Pose camera_from_target = poses.at(row->image).camera_from_target;
    camera_from_target.position *= scale;
    Measurement m;
    m.pose = in.nominal.VectorFromPose(BaseFromPlatform(result.registration, camera_from_target));
    m.legs = row->legs;
    rows.push_back(m);
  }
  return rows;
}

// The FK error the noise model predicts at the held-out poses, or at the
// centre of the pose box without any (expected_error.h).
NoiseExpectation ExpectedNoise(const SessionInputs& in, const std::vector<Measurement>& held_out,
                               const Robot& calibrated) {
  std::vector<Pose> where;
  for (const Measurement& m : held_out) where.push_back(calibrated.PoseFromVector(m.pose));
  if (where.empty()) where.push_back(in.fk_start);
  const ExpectedPoseError expected = ExpectedFkError(calibrated, where, in.config.noise);
  return {in.config.noise, expected.position_rms, expected.orientation_rms_deg};
}

// FK with the nominal and the calibrated robot on the held-out rows.
StatusOr<std::optional<ValidationSummary>> ValidateHeldOut(const SessionInputs& in,
                                                           const std::vector<const LegsRow*>& held_out,
                                                           const std::vector<Measurement>& rows,
                                                           const CameraCalibrationResult& result) {
  if (held_out.empty()) return std::optional<ValidationSummary>();
  StatusOr<ValidationReport> before = Validate(in.nominal, rows);
  if (!before.ok()) return before.status().AsFailure();
  StatusOr<ValidationReport> after = Validate(result.calibration.robot, rows);
  if (!after.ok()) return after.status().AsFailure();
  ValidationSummary summary{static_cast<int>(rows.size()), StatsOf(*before), StatsOf(*after), {}};
  for (size_t j = 0; j < held_out.size(); ++j) {
    const ValidationRow &b = before->rows[j], &a = after->rows[j];
    summary.per_image.push_back({held_out[j]->image, IfOk(b.ok, b.position_error), IfOk(a.ok, a.position_error),
                                 IfOk(b.ok, b.orientation_error_deg), IfOk(a.ok, a.orientation_error_deg)});
  }
  return std::optional<ValidationSummary>(summary);
}

CalibrationReport MakeReport(const std::string& dir, const SessionInputs& in, const SplitRows& split,
                             const CameraCalibrationResult& result) {
  CalibrationReport report;
  report.session = dir;
  report.instrument = in.config.instrument;
  report.images = static_cast<int>(in.legs.size());
  report.unusable_images = split.unusable;
  report.calibration_images = static_cast<int>(split.input.legs.size());
  report.held_out_images = static_cast<int>(split.held_out.size());
  report.length_unit = LengthUnitName(in.nominal.length_unit);
  const Registration& reg = result.registration;
  report.registration = {reg.position_rms,
                         reg.angle_rms_deg,
                         reg.position_max,
                         reg.angle_max_deg,
                         VectorFromPose(reg.base_from_camera, EulerConvention::kXYZ),
                         VectorFromPose(reg.platform_from_target, EulerConvention::kXYZ)};
  report.closure_position_rms = result.calibrated_position_rms;
  report.closure_angle_rms_deg = result.calibrated_angle_rms_deg;
  std::vector<ImageName> names;
  for (const LegsRow* row : split.calibration_rows)
    names.push_back({row->image, row->line > 0 ? std::optional<int>(row->line) : std::nullopt});
  report.closure_by_image = ClosureByImage(result, names);
  report.calibrated_robot = ResultsFile(dir, kCalibratedRobot);
  report.robot = result.calibration.robot;
  FillParameters(result.calibration, &report);
  report.outliers = OutlierReadings(result.calibration, split);
  return report;
}

}  // namespace hexcal::workflow

#include "core/validation.h"

#include "core/forward_kinematics.h"
#include "core/reading_units.h"

namespace hexcal {

StatusOr<ValidationReport> Validate(const Robot& robot, const std::vector<Measurement>& measurements) {
  if (measurements.empty()) return Status::BadInput("validation needs at least one measurement");
  std::vector<LegReadings> readings;
  for (const Measurement& m : measurements) readings.push_back(m.legs);
  if (Status s = CheckReadingsUnit(robot, readings, "measurement"); !s.ok()) return s;
  ValidationReport report;
  std::vector<double> position_errors, orientation_errors;
  for (size_t j = 0; j < measurements.size(); ++j) {
    const Measurement& m = measurements[j];
    if (!m.pose.allFinite() || !m.legs.allFinite()) {
      return Status::BadInput("measurement " + std::to_string(j + 1) + ": pose or leg readings are not finite");
    }
    const Pose measured = robot.PoseFromVector(m.pose);
    StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(robot, m.legs, measured);
    ValidationRow row;
    if (fk.ok()) {
      row.ok = true;
      row.position_error = (fk->pose.position - measured.position).norm();
      row.orientation_error_deg = RadToDeg(RotationDistance(fk->pose.rotation, measured.rotation));
      position_errors.push_back(row.position_error);
      orientation_errors.push_back(row.orientation_error_deg);
    } else {
      row.error = fk.status().message();
      ++report.failed;
    }
    report.rows.push_back(row);
  }
  if (position_errors.empty()) {
    return Status::Failed("forward kinematics failed for all " + std::to_string(measurements.size()) +
                          " measurements with robot '" + robot.name + "'; first: " + report.rows[0].error);
  }
  report.position = SummarizeErrors(position_errors);
  report.orientation_deg = SummarizeErrors(orientation_errors);
  return report;
}

}  // namespace hexcal

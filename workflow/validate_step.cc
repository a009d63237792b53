#include "workflow/validate_step.h"

#include <cstdio>
#include <sstream>

#include "core/robot_io.h"

namespace hexcal::workflow {
namespace {

nlohmann::json StatsJson(const ErrorStats& s) {
  return {{"mean", s.mean}, {"std", s.std}, {"rms", s.rms}, {"max", s.max}};
}

nlohmann::json RowsJson(const ValidationReport& report) {
  nlohmann::json rows = nlohmann::json::array();
  for (size_t j = 0; j < report.rows.size(); ++j) {
    const ValidationRow& row = report.rows[j];
    if (row.ok) {
      rows.push_back({{"measurement", j + 1},
                      {"ok", true},
                      {"position_error", row.position_error},
                      {"orientation_error_deg", row.orientation_error_deg}});
    } else {
      rows.push_back({{"measurement", j + 1}, {"ok", false}, {"error", row.error}});
    }
  }
  return rows;
}

}  // namespace

StatusOr<ValidateResult> ValidateMeasurements(const ValidateRequest& request) {
  StatusOr<Robot> robot = LoadRobot(request.robot);
  if (!robot.ok()) return robot.status();
  StatusOr<std::vector<Measurement>> measurements = LoadMeasurements(request.measurements);
  if (!measurements.ok()) return measurements.status();
  StatusOr<ValidationReport> report = Validate(*robot, *measurements);
  if (!report.ok()) return report.status();  // bad input 2 (e.g. readings in another unit), no FK at all 1
  std::vector<Pose> poses;
  for (const Measurement& m : *measurements) poses.push_back(robot->PoseFromVector(m.pose));
  const ExpectedPoseError expected = ExpectedFkError(*robot, poses, request.noise);
  const std::string unit = LengthUnitName(robot->length_unit);
  return ValidateResult{robot->name, unit, request.measurements, *report, expected,
                        MakeValidationVerdict(*report, expected, unit)};
}

nlohmann::json ToJson(const ValidateResult& result) {
  const ValidationReport& report = result.report;
  return {{"robot", result.robot},
          {"length_unit", result.length_unit},
          {"measurements", report.rows.size()},
          {"converged", report.position.count},
          {"failed", report.failed},
          {"position", StatsJson(report.position)},
          {"orientation_deg", StatsJson(report.orientation_deg)},
          {"rows", RowsJson(report)},
          {"verdict", result.verdict.ToJson()}};
}

std::string FormatValidateSummary(const ValidateResult& result) {
  const ValidationReport& report = result.report;
  std::ostringstream out;
  out << "validation of robot " << result.robot << " on " << report.rows.size() << " measurements ("
      << result.measurements << "): forward kinematics from the readings against the measured pose\n\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-20s %12s %12s %12s %12s\n", "error", "mean", "std", "RMS", "max");
  out << line;
  const std::string position_label = "position (" + result.length_unit + ")";
  for (const auto& [label, s] : {std::pair<std::string, ErrorStats>{position_label, report.position},
                                 std::pair<std::string, ErrorStats>{"orientation (deg)", report.orientation_deg}}) {
    std::snprintf(line, sizeof line, "%-20s %12.4g %12.4g %12.4g %12.4g\n", label.c_str(), s.mean, s.std, s.rms, s.max);
    out << line;
  }
  if (report.failed > 0) {
    out << "\nwarning: forward kinematics failed for " << report.failed << " of " << report.rows.size()
        << " measurements (not in the statistics):\n";
    for (size_t j = 0; j < report.rows.size(); ++j) {
      if (!report.rows[j].ok) out << "  measurement " << j + 1 << ": " << report.rows[j].error << "\n";
    }
  }
  out << "\n" << result.verdict.ToText();
  return out.str();
}

}  // namespace hexcal::workflow

// hexcal validate --robot R --measurements M.csv [--json]
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/robot_io.h"
#include "core/validation.h"

namespace hexcal::cli {
namespace {

struct ValidateOptions {
  std::string robot, measurements;
  bool json = false;
};

nlohmann::json StatsJson(const ErrorStats& s) {
  return {{"mean", s.mean}, {"std", s.std}, {"rms", s.rms}, {"max", s.max}};
}

int RunValidate(const ValidateOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "validate", robot.status());
  StatusOr<std::vector<Measurement>> measurements = LoadMeasurements(options.measurements);
  if (!measurements.ok()) return ReportError(err, "validate", measurements.status());
  StatusOr<ValidationReport> report = Validate(*robot, *measurements);
  if (!report.ok()) return ReportError(err, "validate", report.status());  // bad input 2, no FK at all 1
  const char* unit = LengthUnitName(robot->length_unit);

  if (options.json) {
    nlohmann::json rows = nlohmann::json::array();
    for (size_t j = 0; j < report->rows.size(); ++j) {
      const ValidationRow& row = report->rows[j];
      if (row.ok) {
        rows.push_back({{"measurement", j + 1},
                        {"ok", true},
                        {"position_error", row.position_error},
                        {"orientation_error_deg", row.orientation_error_deg}});
      } else {
        rows.push_back({{"measurement", j + 1}, {"ok", false}, {"error", row.error}});
      }
    }
    out << nlohmann::json{{"robot", robot->name},
                          {"length_unit", unit},
                          {"measurements", report->rows.size()},
                          {"converged", report->position.count},
                          {"failed", report->failed},
                          {"position", StatsJson(report->position)},
                          {"orientation_deg", StatsJson(report->orientation_deg)},
                          {"rows", rows}}
               .dump(2)
        << "\n";
    return kExitOk;
  }
  out << "validation of robot " << robot->name << " on " << report->rows.size() << " measurements ("
      << options.measurements << "): forward kinematics from the readings against the measured pose\n\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-20s %12s %12s %12s %12s\n", "error", "mean", "std", "RMS", "max");
  out << line;
  const std::string position_label = std::string("position (") + unit + ")";
  for (const auto& [label, s] : {std::pair<std::string, ErrorStats>{position_label, report->position},
                                 std::pair<std::string, ErrorStats>{"orientation (deg)", report->orientation_deg}}) {
    std::snprintf(line, sizeof line, "%-20s %12.4g %12.4g %12.4g %12.4g\n", label.c_str(), s.mean, s.std, s.rms, s.max);
    out << line;
  }
  if (report->failed > 0) {
    out << "\nwarning: forward kinematics failed for " << report->failed << " of " << report->rows.size()
        << " measurements (not in the statistics):\n";
    for (size_t j = 0; j < report->rows.size(); ++j) {
      if (!report->rows[j].ok) out << "  measurement " << j + 1 << ": " << report->rows[j].error << "\n";
    }
  }
  return kExitOk;
}

}  // namespace

void AddValidateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* sub = app.add_subcommand("validate", "forward-kinematics errors of a robot on measured poses");
  sub->add_option("--robot", options->robot, "robot file or preset name")->required();
  sub->add_option("--measurements", options->measurements, "measurements CSV: x,y,z,q1,q2,q3,L1..L6")->required();
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunValidate(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

// hexcal ik --robot R --poses P.csv [--out L.csv] [--force] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct IkOptions {
  std::string robot, poses, out;
  bool force = false, json = false;
};

int RunIk(const IkOptions& options, std::ostream& out, std::ostream& err) {
  if (Status s = CheckOutputFree(options.out, options.force); !s.ok()) return ReportError(err, "ik", s);
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "ik", robot.status());
  StatusOr<std::vector<Vector6d>> poses = LoadPoses(options.poses);
  if (!poses.ok()) return ReportError(err, "ik", poses.status());

  std::vector<std::vector<std::string>> rows;
  nlohmann::json json_rows = nlohmann::json::array();
  int feasible_count = 0;
  for (const Vector6d& v : *poses) {
    const Pose pose = robot->PoseFromVector(v);
    const LegReadings readings = InverseKinematics(*robot, pose);
    const ConstraintReport report = EvaluateConstraints(*robot, pose);
    feasible_count += report.feasible;
    std::vector<std::string> row;
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
    for (int i = 0; i < kNumLegs; ++i) row.push_back(FormatNumber(readings[i]));
    row.push_back(report.feasible ? "1" : "0");
    row.push_back(report.feasible ? "" : report.worst_label);
    rows.push_back(row);
    json_rows.push_back({{"pose", PoseJson(*robot, pose)},
                         {"legs", std::vector<double>(readings.data(), readings.data() + kNumLegs)},
                         {"feasible", report.feasible},
                         {"worst_constraint", report.worst_label},
                         {"worst_margin", report.worst_margin}});
  }
  if (!options.out.empty()) {
    const std::vector<std::string> header = {"x",  "y",  "z",  "q1", "q2", "q3",       "L1",
                                             "L2", "L3", "L4", "L5", "L6", "feasible", "violated"};
    if (Status s = WriteCsv(options.out, header, rows); !s.ok()) return ReportError(err, "ik", s);
  }
  if (options.json) {
    out << JsonText(nlohmann::json{
        {"count", poses->size()}, {"feasible", feasible_count}, {"out", options.out}, {"poses", json_rows}});
  } else {
    out << poses->size() << " poses, " << feasible_count << " feasible";
    if (!options.out.empty()) out << "; leg readings written to " << options.out;
    out << "\n";
    if (options.out.empty()) {
      out << FormatCsv({"L1", "L2", "L3", "L4", "L5", "L6", "feasible"}, [&] {
        std::vector<std::vector<std::string>> short_rows;
        for (const auto& row : rows) short_rows.emplace_back(row.begin() + 6, row.begin() + 13);
        return short_rows;
      }());
    }
  }
  return kExitOk;
}

}  // namespace

void AddIkCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<IkOptions>();
  CLI::App* sub = app.add_subcommand("ik", "leg readings L1..L6 of each pose (inverse kinematics)");
  sub->add_option("--robot", options->robot, "robot file or preset name")->required();
  sub->add_option("--poses", options->poses, "pose CSV with columns x,y,z,q1,q2,q3")->required();
  sub->add_option("--out", options->out, "write poses, readings and feasibility to this CSV");
  sub->add_flag("--force", options->force, "overwrite --out if it exists");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunIk(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

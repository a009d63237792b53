// hexcal fk --robot R --legs L1,...,L6 [--all | --start x,y,z,q1,q2,q3] [--json]
//   default   every feasible assembly mode (usually one)
//   --all     every real assembly mode, feasible or not
//   --start   local Newton from a start pose: the mode the robot is tracking
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/fk_homotopy.h"
#include "core/forward_kinematics.h"
#include "core/reading_units.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct FkOptions {
  std::string robot, legs, start;
  bool all = false, json = false;
};

nlohmann::json SolutionJson(const Robot& robot, const Pose& pose, bool at_singularity) {
  const ConstraintReport report = EvaluateConstraints(robot, pose);
  nlohmann::json j = PoseJson(robot, pose);
  j["feasible"] = report.feasible;
  j["at_singularity"] = at_singularity;
  if (!report.feasible) j["violated"] = report.worst_label;
  return j;
}

void PrintSolutions(const Robot& robot, const std::vector<Pose>& poses, const std::vector<bool>& singular,
                    std::ostream& out) {
  out << "   x            y            z            q1           q2           q3           feasible\n";
  for (size_t k = 0; k < poses.size(); ++k) {
    const Pose& pose = poses[k];
    const Vector6d v = robot.VectorFromPose(pose);
    char line[200];
    std::snprintf(line, sizeof line, "%-12.6g %-12.6g %-12.6g %-12.6g %-12.6g %-12.6g ", v[0], v[1], v[2], v[3], v[4],
                  v[5]);
    const ConstraintReport report = EvaluateConstraints(robot, pose);
    out << "   " << line << (report.feasible ? "yes" : "no (" + report.worst_label + ")")
        << (singular[k] ? "  at a singularity" : "") << "\n";
  }
}

int RunFk(const FkOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "fk", robot.status());
  StatusOr<std::vector<double>> legs = ParseNumberList(options.legs, kNumLegs, "--legs");
  if (!legs.ok()) return ReportError(err, "fk", legs.status());
  const LegReadings readings = Eigen::Map<const LegReadings>(legs->data());
  if (Status s = CheckReadingsUnit(*robot, {readings}, ""); !s.ok()) return ReportError(err, "fk", s);

  std::vector<Pose> poses;
  std::vector<bool> singular;  // per pose: at a parallel singularity
  nlohmann::json summary;
  if (!options.start.empty()) {
    StatusOr<std::vector<double>> start = ParseNumberList(options.start, 6, "--start");
    if (!start.ok()) return ReportError(err, "fk", start.status());
    StatusOr<LocalFkResult> local =
        ForwardKinematicsLocal(*robot, readings, robot->PoseFromVector(Eigen::Map<const Vector6d>(start->data())));
    if (!local.ok()) return ReportError(err, "fk", local.status());
    poses.push_back(local->pose);
    singular.push_back(false);  // a singular local solution is an error
    summary = {{"method", "local"}, {"iterations", local->iterations}, {"max_residual", local->max_residual}};
  } else {
    StatusOr<FkAllResult> modes = ForwardKinematicsAll(*robot, readings);
    if (!modes.ok()) return ReportError(err, "fk", modes.status());
    for (size_t k = 0; k < modes->poses.size(); ++k) {
      if (!options.all && !IsFeasible(*robot, modes->poses[k])) continue;
      poses.push_back(modes->poses[k]);
      singular.push_back(modes->at_singularity[k]);
    }
    summary = {{"method", "homotopy"},
               {"real_modes", modes->poses.size()},
               {"complex_solutions", modes->complex_solutions},
               {"failed_paths", modes->failed_paths},
               {"tracked_paths", modes->tracked_paths},
               {"singular_modes", modes->SingularCount()}};
  }

  if (options.json) {
    nlohmann::json solutions = nlohmann::json::array();
    for (size_t k = 0; k < poses.size(); ++k) solutions.push_back(SolutionJson(*robot, poses[k], singular[k]));
    summary["solutions"] = solutions;
    out << JsonText(summary);
  } else {
    if (summary["method"] == "homotopy") {
      out << summary["real_modes"] << " real assembly modes (" << summary["complex_solutions"] << " complex solutions, "
          << summary["failed_paths"] << " singular paths); showing " << (options.all ? "all" : "the feasible ones")
          << ":\n";
    }
    if (poses.empty()) out << "   (none)\n";
    PrintSolutions(*robot, poses, singular, out);
    if (summary.value("singular_modes", 0) > 0) {
      out << "warning: " << summary["singular_modes"]
          << " mode(s) at a parallel singularity (a double root of the FK equations): the readings do not "
             "determine the platform's motion there\n";
    }
  }
  return kExitOk;
}

}  // namespace

void AddFkCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<FkOptions>();
  CLI::App* sub = app.add_subcommand("fk", "platform poses for given leg readings (forward kinematics)");
  sub->add_option("--robot", options->robot, "robot file or preset name")->required();
  sub->add_option("--legs", options->legs, "six readings L1,...,L6 in the robot's length unit")->required();
  auto* all = sub->add_flag("--all", options->all, "list every real assembly mode, feasible or not");
  sub->add_option("--start", options->start, "local Newton from this pose x,y,z,q1,q2,q3 (degrees)")->excludes(all);
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunFk(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

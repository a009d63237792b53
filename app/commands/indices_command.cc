// hexcal indices --robot R --poses P.csv [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/csv.h"
#include "core/observability.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct IndicesOptions {
  std::string robot, poses;
  bool json = false;
};

int RunIndices(const IndicesOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "indices", robot.status());
  StatusOr<std::vector<Vector6d>> vectors = LoadPoses(options.poses);
  if (!vectors.ok()) return ReportError(err, "indices", vectors.status());
  std::vector<Pose> poses;
  int infeasible = 0;
  for (const Vector6d& v : *vectors) {
    poses.push_back(robot->PoseFromVector(v));
    infeasible += !IsFeasible(*robot, poses.back());
  }
  const ObservabilityIndices indices = ComputeIndices(*robot, poses);
  if (options.json) {
    nlohmann::json j = IndicesJson(indices);
    j["infeasible_poses"] = infeasible;
    j["length_unit"] = LengthUnitName(robot->length_unit);
    const SingularValues sigma = SingularValuesOf(ComputeInformation(*robot, poses));
    j["singular_values"] = std::vector<double>(sigma.data(), sigma.data() + kNumParams);
    out << JsonText(j);
    return kExitOk;
  }
  out << "observability of " << poses.size() << " poses (robot " << robot->name << ", lengths in "
      << LengthUnitName(robot->length_unit) << ")\n"
      << "  O1 = " << indices.o1 << "\n  O2 = " << indices.o2 << "\n  O3 = " << indices.o3 << "\n  O4 = " << indices.o4
      << "\n  sigma_max = " << indices.sigma_max << ", sigma_min = " << indices.sigma_min << "\n";
  if (infeasible > 0) out << "warning: " << infeasible << " poses violate the robot's constraints\n";
  if (poses.size() < static_cast<size_t>(kParamsPerLeg)) {
    out << "warning: fewer than 7 poses cannot identify the 7 parameters of a leg (O3 = 0)\n";
  }
  return kExitOk;
}

}  // namespace

void AddIndicesCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<IndicesOptions>();
  CLI::App* sub = app.add_subcommand("indices", "observability indices O1..O4 of a pose set");
  sub->add_option("--robot", options->robot, "robot file or preset name")->required();
  sub->add_option("--poses", options->poses, "pose CSV with columns x,y,z,q1,q2,q3")->required();
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunIndices(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

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
  const std::string unit = LengthUnitName(robot->length_unit);
  out << "observability of " << poses.size() << " poses (robot " << robot->name << ", lengths in " << unit
      << "; paper section 2, each larger for a better pose set)\n";
  const double values[4] = {indices.o1, indices.o2, indices.o3, indices.o4};
  for (int k = 1; k <= 4; ++k) {
    const std::string with_unit = IndexUnit(k, unit).empty() ? "" : " " + IndexUnit(k, unit);
    out << "  O" << k << " = " << values[k - 1] << with_unit << ": " << IndexMeaning(k) << "\n";
  }
  out << "  sigma_max = " << indices.sigma_max << " " << unit << ", sigma_min = " << indices.sigma_min << " " << unit
      << " (singular values of the identification Jacobian J_P)\n";
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

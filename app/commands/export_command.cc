// hexcal export --robot R --format linuxcnc-hal|robot --out FILE [--machine-unit mm|inch] [--force]
//
// Writes a robot's geometry for a controller: `linuxcnc-hal` is the
// `setp genhexkins.base.N.*` / `platform.N.*` lines of LinuxCNC's hexapod
// kinematics, in the machine's linear unit (workflow/linuxcnc_geometry.h,
// docs/acquisition.md). Written atomically.
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "core/robot_io.h"
#include "workflow/linuxcnc_geometry.h"

namespace hexcal::cli {
namespace {

struct ExportOptions {
  std::string robot, format = "linuxcnc-hal", out, machine_unit = "mm";
  bool force = false;
};

int RunExport(const ExportOptions& options, std::ostream& out, std::ostream& err) {
  if (options.format != "linuxcnc-hal" && options.format != "robot")
    return ReportError(err, "export",
                       Status::Error("--format: unknown format '" + options.format + "'; accepted: linuxcnc-hal, robot"));
  const std::optional<workflow::MachineUnit> unit = workflow::ParseMachineUnit(options.machine_unit);
  if (!unit)
    return ReportError(err, "export",
                       Status::Error("--machine-unit: '" + options.machine_unit +
                                     "' is not a LinuxCNC linear unit; accepted: mm, inch"));
  if (Status s = CheckOutputFree(options.out, options.force); !s.ok()) return ReportError(err, "export", s);
  StatusOr<Robot> robot = LoadRobot(options.robot);
  if (!robot.ok()) return ReportError(err, "export", robot.status());
  if (options.format == "robot") {  // a preset as a file, e.g. the robot a machine runs with
    if (Status s = WriteFileAtomically(options.out, RobotToYaml(*robot)); !s.ok()) return ReportError(err, "export", s);
    out << "wrote " << options.out << ": robot '" << robot->name << "' (" << LengthUnitName(robot->length_unit)
        << ")\n";
    return kExitOk;
  }
  if (Status s = WriteFileAtomically(options.out, workflow::GenhexkinsHal(*robot, *unit)); !s.ok())
    return ReportError(err, "export", s);
  out << "wrote " << options.out << ": genhexkins geometry of robot '" << robot->name << "' in "
      << workflow::MachineUnitName(*unit) << " (robot file in " << LengthUnitName(robot->length_unit) << ")\n";
  return kExitOk;
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "write a robot's geometry for a controller (LinuxCNC genhexkins HAL)");
  sub->add_option("--robot", options->robot, "robot file or preset name (a calibrated robot file, typically)")
      ->required();
  sub->add_option("--format", options->format, "output format: linuxcnc-hal (genhexkins pins), robot (the robot file)")->capture_default_str();
  sub->add_option("--out", options->out, "file to write")->required();
  sub->add_option("--machine-unit", options->machine_unit,
                  "the machine's [TRAJ] LINEAR_UNITS: mm or inch (lengths are converted from the robot's unit)")
      ->capture_default_str();
  sub->add_flag("--force", options->force, "overwrite an existing --out file");
  sub->callback([=] { *exit_code = RunExport(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

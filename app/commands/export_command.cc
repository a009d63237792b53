// hexcal export --robot R --format linuxcnc-hal|robot --out FILE [--machine-unit mm|inch] [--force] [--json]
//               [--push [--yes] [--halcmd PATH] [--running-robot FILE]]
//
// Writes a robot's geometry for a controller: `linuxcnc-hal` is the
// `setp genhexkins.base.N.*` / `platform.N.*` lines of LinuxCNC's hexapod
// kinematics, in the machine's linear unit (workflow/linuxcnc_geometry.h,
// docs/acquisition.md). Written atomically. --push then loads it into the
// running machine (workflow/hal_push.h) once the operator confirms.
#include <unistd.h>

#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "core/robot_io.h"
#include "workflow/hal_push.h"
#include "workflow/linuxcnc_geometry.h"

namespace hexcal::cli {
namespace {

struct ExportOptions {
  std::string robot, format = "linuxcnc-hal", out, machine_unit = "mm";
  bool force = false, json = false;
  bool push = false, yes = false;  // --push: into the running machine, after a confirmation (or --yes)
  std::string halcmd = "halcmd", running_robot;
};

// The operator's yes: --yes, or "y" typed at a terminal. A push changes a
// moving machine's kinematics, so a script must say --yes.
Status Confirm(const ExportOptions& options, const Robot& robot, int pins, std::ostream& out) {
  if (options.yes) return Status::Ok();
  if (!isatty(STDIN_FILENO))
    return Status::Error("--push changes the kinematics of a running machine: confirm with --yes "
                         "(standard input is not a terminal)");
  out << "Set " << pins << " genhexkins pins of the running LinuxCNC to robot '" << robot.name
      << "'? The world pose is held, so the legs step to the new geometry's lengths. [y/N] " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  if (answer == "y" || answer == "Y" || answer == "yes") return Status::Ok();
  return Status::Cancelled();
}

// --push: the written HAL file into the running machine (workflow/hal_push.h),
// then what the INI must change for the offsets l, which are not pins.
int PushToMachine(const ExportOptions& options, const Robot& robot, workflow::MachineUnit unit, std::ostream& out,
                  std::ostream& err) {
  const int pins = workflow::CountHalPins(workflow::GenhexkinsHal(robot, unit));
  if (Status s = Confirm(options, robot, pins, out); !s.ok()) {
    if (s.cancelled()) return out << "not pushed: the machine is unchanged\n", kExitFailure;
    return ReportError(err, "export", s);
  }
  StatusOr<int> pushed = workflow::PushHalFile(options.halcmd, options.out);
  if (!pushed.ok()) return ReportError(err, "export", pushed.status());
  out << "pushed " << *pushed << " pins into the running LinuxCNC (" << options.halcmd << " -f " << options.out
      << ")\n";
  if (options.running_robot.empty()) {
    out << "the offsets l are the joints' homes (INI [JOINT_n] HOME, HOME_OFFSET): give --running-robot to see "
           "how they change, then home again\n";
    return kExitOk;
  }
  StatusOr<Robot> running = LoadRobot(options.running_robot);
  if (!running.ok()) return ReportError(err, "export", running.status());
  const std::string shifts = workflow::HomeOffsetShifts(*running, robot, unit);
  out << (shifts.empty() ? "the offsets l are unchanged: no INI change\n"
                         : "the offsets l changed: in the machine's INI, then home again:\n" + shifts);
  return kExitOk;
}

void PrintWritten(const ExportOptions& options, const Robot& robot, workflow::MachineUnit unit, std::ostream& out) {
  const bool hal = options.format == "linuxcnc-hal";
  if (options.json) {
    nlohmann::json json{{"out", options.out},
                        {"format", options.format},
                        {"robot", robot.name},
                        {"length_unit", LengthUnitName(robot.length_unit)}};
    if (hal) json["machine_unit"] = workflow::MachineUnitName(unit);
    out << JsonText(json);
  } else if (hal) {
    out << "wrote " << options.out << ": genhexkins geometry of robot '" << robot.name << "' in "
        << workflow::MachineUnitName(unit) << " (robot file in " << LengthUnitName(robot.length_unit) << ")\n";
  } else {
    out << "wrote " << options.out << ": robot '" << robot.name << "' (" << LengthUnitName(robot.length_unit) << ")\n";
  }
}

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
  if (options.push && options.format != "linuxcnc-hal")
    return ReportError(err, "export", Status::Error("--push needs --format linuxcnc-hal"));
  // --push asks on the terminal and prints halcmd's answers: not one JSON object.
  if (options.push && options.json) return ReportError(err, "export", Status::Error("--json cannot go with --push"));
  const bool hal = options.format == "linuxcnc-hal";  // else the robot file, e.g. of a preset a machine runs with
  if (Status s = WriteFileAtomically(options.out, hal ? workflow::GenhexkinsHal(*robot, *unit) : RobotToYaml(*robot));
      !s.ok())
    return ReportError(err, "export", s);
  PrintWritten(options, *robot, *unit, out);
  return options.push ? PushToMachine(options, *robot, *unit, out, err) : kExitOk;
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
  sub->add_flag("--json", options->json, "print one JSON object on stdout (not with --push)");
  sub->add_flag("--push", options->push,
                "also load the pins into the running LinuxCNC with halcmd, after a confirmation");
  sub->add_flag("--yes", options->yes, "confirm --push without asking (scripts)");
  sub->add_option("--halcmd", options->halcmd, "the halcmd to run for --push")->capture_default_str();
  sub->add_option("--running-robot", options->running_robot,
                  "with --push: the robot file the machine runs with now, to print the INI's home changes");
  sub->callback([=] { *exit_code = RunExport(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

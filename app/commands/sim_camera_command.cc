// hexcal sim-camera --session DIR --machine-robot FILE [--machine-unit mm|inch]
//                   [--seed N] [--interface ADDRESS] [--serial NAME] [--python PATH]
//
// A GenICam (GigE Vision) camera of the sim world that follows a LinuxCNC
// machine: the closed loop in simulation (docs/acquisition.md). The session's
// hidden true robot, camera and target are drawn from --seed as `acquire
// --controller sim` draws them and written to DIR/truth/; the platform sits
// where the true robot puts the joints of the LinuxCNC machine running on this
// host (sim/machine_follower.h);
// the camera serves the rendered board through libaravis' fake GigE Vision
// camera on --interface, for `hexcal acquire --camera aravis:NAME`. Runs until
// Ctrl-C or SIGTERM.
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "sim/machine_follower.h"
#include "sim/sim_world.h"
#ifdef HEXCAL_HAVE_ARAVIS
#include "devices/fake_genicam_camera.h"
#endif

namespace hexcal::cli {
namespace {

struct SimCameraOptions {
  std::string session, machine_robot, machine_unit = "mm", interface = "127.0.0.1", serial = "HEXCAL01";
  std::string python = "/usr/bin/python3";
  uint64_t seed = 1;
};

#ifdef HEXCAL_HAVE_ARAVIS
std::atomic<bool> stop_serving{false};
void StopServing(int) { stop_serving = true; }

// Serves until a signal; a change of the follower's problem is printed once.
void ServeUntilStopped(const workflow::MachineFollower& follower, std::ostream& err) {
  std::string reported;
  while (!stop_serving) {
    const std::string problem = follower.Problem();
    if (problem != reported) err << "sim-camera: " << (problem.empty() ? "following again" : problem) << std::endl;
    reported = problem;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

int RunSimCamera(const SimCameraOptions& options, std::ostream& out, std::ostream& err) {
  const std::optional<workflow::MachineUnit> unit = workflow::ParseMachineUnit(options.machine_unit);
  if (!unit)
    return ReportError(err, "sim-camera",
                       Status::BadInput("--machine-unit: '" + options.machine_unit + "'; accepted: mm, inch"));
  StatusOr<std::shared_ptr<workflow::SimWorld>> world = workflow::SimWorld::ForSession(options.session, options.seed);
  if (!world.ok()) return ReportError(err, "sim-camera", world.status());
  if (Status s = (*world)->WriteTruth(options.session); !s.ok()) return ReportError(err, "sim-camera", s);
  workflow::FollowerOptions follow;
  follow.python = options.python;
  follow.unit = *unit;
  StatusOr<std::unique_ptr<workflow::MachineFollower>> follower =
      workflow::MachineFollower::Start(options.machine_robot, *world, follow);
  if (!follower.ok()) return ReportError(err, "sim-camera", follower.status());
  workflow::FakeCameraOptions camera_options;
  camera_options.interface = options.interface;
  camera_options.serial = options.serial;
  workflow::MachineFollower* source = follower->get();
  StatusOr<std::unique_ptr<workflow::FakeGenICamCamera>> camera =
      workflow::FakeGenICamCamera::Start(camera_options, [source] { return source->LatestFrame(); });
  if (!camera.ok()) return ReportError(err, "sim-camera", camera.status());
  std::signal(SIGINT, StopServing);
  std::signal(SIGTERM, StopServing);
  out << "sim-camera: serving aravis:" << (*camera)->DeviceId() << " on " << options.interface
      << ", following this host's LinuxCNC; the truth is in " << options.session << "/truth" << std::endl;
  ServeUntilStopped(**follower, err);
  out << "sim-camera: stopped after " << (*follower)->frames_rendered() << " rendered frames" << std::endl;
  return kExitOk;
}
#else
int RunSimCamera(const SimCameraOptions&, std::ostream&, std::ostream& err) {
  return ReportError(err, "sim-camera",
                     Status::BadInput("this hexcal was built without Aravis (install libaravis-dev: "
                                      "scripts/install-deps.sh)"));
}
#endif

}  // namespace

void AddSimCameraCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SimCameraOptions>();
  CLI::App* sub = app.add_subcommand(
      "sim-camera", "serve a GenICam camera of the sim world that follows this host's LinuxCNC (closed-loop simulation)");
  sub->add_option("--session", options->session, "session folder: its robot, camera and target; truth written there")
      ->required();
  sub->add_option("--machine-robot", options->machine_robot,
                  "the robot file the machine runs with (its offsets l are the joints' homes)")
      ->required();
  sub->add_option("--machine-unit", options->machine_unit, "the machine's [TRAJ] LINEAR_UNITS: mm or inch")
      ->capture_default_str();
  sub->add_option("--python", options->python, "a Python 3 with LinuxCNC's module linuxcnc")->capture_default_str();
  sub->add_option("--seed", options->seed, "seed of the hidden truth (as acquire --controller sim --seed)")
      ->capture_default_str();
  sub->add_option("--interface", options->interface, "IPv4 address to serve the camera on")->capture_default_str();
  sub->add_option("--serial", options->serial, "the camera's serial number (one camera per address)")
      ->capture_default_str();
  sub->callback([=] { *exit_code = RunSimCamera(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

#include "devices/linuxcnc_push.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <thread>

#include "core/atomic_file.h"
#include "core/forward_kinematics.h"
#include "core/robot_io.h"
#include "devices/controller.h"
#include "devices/device_urls.h"
#include "devices/hal_push.h"
#include "devices/linuxcnc_controller.h"
#include "devices/linuxcnc_geometry.h"
#include "devices/linuxcnc_ini.h"

namespace hexcal::workflow {
namespace {

// halcmd prints float pins with 7 significant digits: a live pin agrees with
// a file's value within this share of the value (at least of 1 unit).
constexpr double kPinAgreement = 2e-6;
// After homing again, each joint is at its new HOME within this, machine units.
constexpr double kHomeTolerance = 1e-4;

PinSet SetpPins(const std::string& hal_text) {
  PinSet pins;
  std::istringstream lines(hal_text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string command, pin;
    double value = 0;
    if (words >> command >> pin >> value && command == "setp") {
      pins.names.push_back(pin);
      pins.values.push_back(value);
    }
  }
  return pins;
}

// The ini.N.* pins of milltask (LinuxCNC's inihal) for the four INI values of
// each joint, shifted by `shifts`.
PinSet IniPins(const MachineIni& ini, const std::array<double, 6>& shifts) {
  PinSet pins;
  for (int n = 0; n < 6; ++n) {
    const IniJoint& joint = ini.joints[n];
    const std::pair<const char*, double> values[4] = {{"home", joint.home},
                                                      {"home_offset", joint.home_offset},
                                                      {"min_limit", joint.min_limit},
                                                      {"max_limit", joint.max_limit}};
    for (const auto& [key, value] : values) {
      pins.names.push_back("ini." + std::to_string(n) + "." + key);
      pins.values.push_back(value + shifts[n]);
    }
  }
  return pins;
}

std::string SetpText(const PinSet& pins) {
  std::string text;
  for (size_t k = 0; k < pins.names.size(); ++k)
    text += "setp " + pins.names[k] + " " + ExactFixedNumber(pins.values[k]) + "\n";
  return text;
}

// The live pins are `expected` (the files' values), or bad input naming the
// first that is not and `source`.
Status CheckLivePins(const std::string& halcmd, const PinSet& expected, const std::string& source) {
  StatusOr<std::vector<double>> live = ReadHalPins(halcmd, expected.names);
  // milltask makes its ini.N.* pins up to ~0.5 s after linuxcncrsh opens its
  // port (seen with 2.9): a machine that has just started gets 5 s.
  for (int retry = 0; retry < 10 && !live.ok() && live.status().message().find("not found") != std::string::npos;
       ++retry) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    live = ReadHalPins(halcmd, expected.names);
  }
  if (!live.ok()) return live.status();
  for (size_t k = 0; k < expected.names.size(); ++k) {
    const double want = expected.values[k], got = (*live)[k];
    if (std::abs(got - want) > kPinAgreement * std::max(1.0, std::abs(want))) {
      return Status::BadInput("the running machine's " + expected.names[k] + " is " + ExactFixedNumber(got) + ", " +
                              source + " says " + ExactFixedNumber(want) +
                              ": the files do not describe the running machine; nothing was changed");
    }
  }
  return Status::Ok();
}

// The INI's HALFILE that sets the genhexkins pins (the one the calibrated
// pins replace, so that a restart keeps them): a file beside the INI, not a
// LIB: one, holding `setp genhexkins.base.` lines.
StatusOr<std::string> GenhexkinsHalFile(const std::string& ini_path, const MachineIni& ini) {
  const std::filesystem::path folder = std::filesystem::path(ini_path).parent_path();
  for (const std::string& value : ini.hal_files) {
    if (value.rfind("LIB:", 0) == 0 || value.find_first_of(" \t") != std::string::npos) continue;
    const std::filesystem::path path = std::filesystem::path(value).is_absolute() ? std::filesystem::path(value) : folder / value;
    StatusOr<std::string> text = ReadFileToString(path.string());
    if (text.ok() && text->find("setp genhexkins.base.") != std::string::npos) return path.string();
  }
  return Status::BadInput(ini_path +
                          ": no [HAL] HALFILE beside it sets the genhexkins pins (setp genhexkins.base...): "
                          "a restart would bring the old geometry back; put the pins in a HAL file of their own, "
                          "listed as HALFILE");
}

}  // namespace

StatusOr<PushPlan> PlanPush(const PushRequest& request) {
  for (const Robot* robot : {&request.running, &request.calibrated})
    if (Status s = CheckRobotForMachine(*robot); !s.ok()) return s;
  StatusOr<std::string> ini_text = ReadFileToString(request.ini_path);
  if (!ini_text.ok()) return ini_text.status();
  StatusOr<MachineIni> ini = ParseMachineIni(*ini_text);
  if (!ini.ok()) return Status::BadInput(request.ini_path + ": " + ini.status().message());
  PushPlan plan{*ini, {}, {}, {}, {}};
  StatusOr<std::array<double, 6>> shifts = HomeShifts(request.running, request.calibrated, ini->unit);
  if (!shifts.ok()) return shifts.status();
  plan.shifts = *shifts;
  const std::string old_hal = GenhexkinsHal(request.running, ini->unit);
  const std::string new_hal = GenhexkinsHal(request.calibrated, ini->unit);
  if (Status s = CheckLivePins(request.halcmd, SetpPins(old_hal), "running robot " + request.running_robot_path);
      !s.ok())
    return s;
  if (Status s = CheckLivePins(request.halcmd, IniPins(*ini, {}), request.ini_path); !s.ok()) return s;
  StatusOr<std::string> hal_file = GenhexkinsHalFile(request.ini_path, *ini);
  if (!hal_file.ok()) return hal_file.status();
  StatusOr<std::string> old_hal_file = ReadFileToString(*hal_file);
  StatusOr<std::string> old_robot_file = ReadFileToString(request.running_robot_path);
  for (const Status& s : {old_hal_file.status(), old_robot_file.status()})
    if (!s.ok()) return s;
  plan.files = {{request.ini_path, *ini_text, ShiftedIniText(*ini, plan.shifts)},
                {*hal_file, *old_hal_file, new_hal},
                {request.running_robot_path, *old_robot_file, RobotToYaml(request.calibrated)}};
  for (const FileChange& file : plan.files)
    if (Status s = CheckOutputFree(file.path, /*force=*/true); !s.ok()) return s;
  plan.old_pins = SetpPins(old_hal);
  plan.new_pins = SetpPins(new_hal);
  const PinSet old_ini = IniPins(*ini, {}), new_ini = IniPins(*ini, plan.shifts);
  for (const auto& [to, from] : {std::pair{&plan.old_pins, &old_ini}, std::pair{&plan.new_pins, &new_ini}}) {
    to->names.insert(to->names.end(), from->names.begin(), from->names.end());
    to->values.insert(to->values.end(), from->values.begin(), from->values.end());
  }
  return plan;
}

namespace {

Status WriteFiles(const std::vector<FileChange>& files, bool new_text) {
  for (const FileChange& file : files)
    if (Status s = WriteFileAtomically(file.path, new_text ? file.new_text : file.old_text); !s.ok()) return s;
  return Status::Ok();
}

// Where the running robot's platform is when every joint is at its
// HOME_OFFSET, the home switches (a simulated machine homes where it stands).
StatusOr<Vector6d> SwitchPose(const Robot& running, const MachineIni& ini) {
  Vector6d joints;
  for (int n = 0; n < 6; ++n) joints[n] = ini.joints[n].home_offset;
  const LegReadings readings = ReadingsFromJoints(running, joints, ini.unit);
  StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(running, readings, running.PoseFromVector(WorkspaceCentre(running)));
  if (!fk.ok()) return Status::Failed("no pose of the running robot puts its joints at HOME_OFFSET: " + fk.status().message());
  return running.VectorFromPose(fk->pose);
}

// The joints' HOME values, shifted.
Vector6d HomeJoints(const MachineIni& ini, const std::array<double, 6>& shifts) {
  Vector6d joints;
  for (int n = 0; n < 6; ++n) joints[n] = ini.joints[n].home + shifts[n];
  return joints;
}

// Homes again and checks every joint is at its new HOME (read back through
// the controller, which converts joints with the running robot's l).
StatusOr<double> HomeAgain(Controller& machine, const Robot& running, const MachineIni& ini,
                           const std::array<double, 6>& shifts) {
  if (Status s = RehomeLinuxCnc(machine, HomeJoints(ini, shifts), kHomeTolerance); !s.ok()) return s;
  StatusOr<LegReadings> legs = machine.ReadLegs();
  if (!legs.ok()) return legs.status();
  const Vector6d joints = JointsFromReadings(running, *legs, ini.unit);
  const double error = (joints - HomeJoints(ini, shifts)).cwiseAbs().maxCoeff();
  if (!(error <= kHomeTolerance))
    return Status::Failed("after homing again a joint is " + ExactFixedNumber(error) + " " + MachineUnitName(ini.unit) +
                          " from its new HOME");
  return error;
}

// The change itself: pins, files, homing. On a failure, the old pins and
// files are put back and the machine homed again with them.
StatusOr<double> ApplyPush(const PushRequest& request, const PushPlan& plan, Controller& machine,
                           std::ostream& progress) {
  if (StatusOr<std::string> set = RunHalText(request.halcmd, SetpText(plan.new_pins)); !set.ok()) {
    const bool back = RunHalText(request.halcmd, SetpText(plan.old_pins)).ok();
    return Status::Failed(set.status().message() + (back ? "; the old pins were set again, no file was changed"
                                                         : "; setting the old pins again failed too: check the "
                                                           "machine before moving it"));
  }
  Status written = WriteFiles(plan.files, /*new_text=*/true);
  StatusOr<double> homed = written.ok() ? HomeAgain(machine, request.running, plan.ini, plan.shifts)
                                        : StatusOr<double>(written);
  if (homed.ok()) return homed;
  progress << "the push failed: putting the old pins and files back and homing again\n" << std::flush;
  const Status pins_back = RunHalText(request.halcmd, SetpText(plan.old_pins)).status();
  const Status files_back = WriteFiles(plan.files, /*new_text=*/false);
  const Status homed_back =
      pins_back.ok() ? RehomeLinuxCnc(machine, HomeJoints(plan.ini, {}), kHomeTolerance) : pins_back;
  const bool restored = pins_back.ok() && files_back.ok() && homed_back.ok();
  return Status::Failed(homed.status().message() +
                        (restored ? "; the machine runs with its old geometry again"
                                  : "; putting the old geometry back failed too (" +
                                        (files_back.ok() ? homed_back : files_back).message() +
                                        "): check the machine and its files before moving it"));
}

}  // namespace

StatusOr<PushReport> PushCalibration(const PushRequest& request, const PushPlan& plan, std::ostream& progress) {
  StatusOr<Vector6d> switches = SwitchPose(request.running, plan.ini);
  if (!switches.ok()) return switches.status();
  ControllerOptions options;
  options.robot = std::make_shared<const Robot>(request.running);
  StatusOr<std::unique_ptr<Controller>> machine = OpenController(request.controller_url, options);
  if (!machine.ok()) return machine.status();
  progress << "moving to the home switches:";
  for (double value : *switches) progress << " " << FixedNumber(value, 6);
  progress << "\n" << std::flush;
  if (Status s = (*machine)->MoveTo(*switches); !s.ok()) return s;
  if (Status s = (*machine)->WaitSettled(0); !s.ok()) return s;
  progress << "setting " << plan.new_pins.names.size() << " pins, writing the INI, HAL and robot files, homing again\n"
           << std::flush;
  StatusOr<double> home_error = ApplyPush(request, plan, **machine, progress);
  if (!home_error.ok()) return home_error.status();
  PushReport report;
  report.pins = static_cast<int>(plan.new_pins.names.size());
  report.shifts = plan.shifts;
  report.ini_changes = IniChangeText(plan.ini, plan.shifts);
  for (const FileChange& file : plan.files) report.files.push_back(file.path);
  report.home_error = *home_error;
  report.unit = plan.ini.unit;
  return report;
}

}  // namespace hexcal::workflow

// Loading a calibrated robot into a running LinuxCNC hexapod, all of it or
// nothing (`hexcal export --push`, docs/acquisition.md, "Loading a
// calibration into LinuxCNC"): the genhexkins pins (a, b) and the joints'
// homes and limits (the offsets l, devices/linuxcnc_ini.h), live and in the
// machine's files, then homing again.
//
// Before anything changes: the INI parses, its unit is the export's, the
// machine's live pins are the running robot's and the INI's (so the files
// describe this machine), the calibrated robot is the same machine
// (HomeShifts). Then, through the controller: the platform goes where its
// joints sit at HOME_OFFSET (the home switches), the pins and the INI's
// values are set in one halcmd run, the INI, the HAL file holding the
// genhexkins pins and the running-robot file are replaced (atomically), and
// the joints are homed again; the check is that every joint ends at its new
// HOME. A failure after the first change puts the old pins, values and files
// back and says so.
//
//   PushRequest request{running, calibrated, "machine.ini", "robot.yaml", "linuxcnc://127.0.0.1:5007"};
//   StatusOr<PushPlan> plan = PlanPush(request);         // every check; nothing changes
//   StatusOr<PushReport> report = PushCalibration(request, *plan, std::cout);
#pragma once

#include <array>
#include <ostream>
#include <string>

#include "core/robot.h"
#include "core/status.h"
#include "devices/linuxcnc_ini.h"

namespace hexcal::workflow {

struct PushRequest {
  Robot running;     // the robot the machine runs with now
  Robot calibrated;  // the robot to load
  std::string ini_path;            // the machine's INI
  std::string running_robot_path;  // `running`'s file: replaced by `calibrated` after the push
  std::string controller_url;      // linuxcnc://HOST:PORT, for moving and homing
  std::string halcmd = "halcmd";
};

struct PushReport {
  int pins = 0;                      // genhexkins pins set
  std::array<double, 6> shifts{};    // each joint's home moved by, machine units
  std::string ini_changes;           // IniChangeText
  std::vector<std::string> files;    // the files replaced
  double home_error = 0;             // max |joint − new HOME| after homing, machine units
  MachineUnit unit = MachineUnit::kMillimetre;  // the machine's
};

// HAL pins and their values, in the order they are set.
struct PinSet {
  std::vector<std::string> names;
  std::vector<double> values;
};

// A file the push replaces, with its text before and after.
struct FileChange {
  std::string path, old_text, new_text;
};

// What a push will change, all of it checked before the machine is touched.
struct PushPlan {
  MachineIni ini;
  std::array<double, 6> shifts{};  // HomeShifts, machine units
  PinSet old_pins, new_pins;       // genhexkins.* and ini.N.* together
  std::vector<FileChange> files;   // the INI, its genhexkins HAL file, the running-robot file
};

// The checks of the header comment; bad input says which failed and that
// nothing was changed. Reads the machine's pins through halcmd.
StatusOr<PushPlan> PlanPush(const PushRequest& request);

// Carries out a plan of PlanPush; `progress` gets a line per stage.
StatusOr<PushReport> PushCalibration(const PushRequest& request, const PushPlan& plan, std::ostream& progress);

}  // namespace hexcal::workflow

// Loading a robot's geometry into a running LinuxCNC (`hexcal export
// --format linuxcnc-hal --push`, docs/acquisition.md): the `setp` lines of
// GenhexkinsHal run through `halcmd -f FILE`. genhexkins reads its pins every
// servo cycle, so the change acts at once: the world pose is held and the
// joints step (../shared/devices.md). The offsets l are not pins: they are the
// joints' home positions in the machine's INI, so they change only with the
// INI and homing again (HomeOffsetShifts says by how much).
//
// halcmd must reach the running machine's HAL: as root, with the same
// RTAPI_UID and RTAPI_FIFO_PATH as the machine (scripts/linuxcnc-sim.sh env).
//
//   StatusOr<int> pins = PushHalFile("halcmd", "calibrated.hal");  // 37 pins set
#pragma once

#include <string>

#include "core/robot.h"
#include "core/status.h"
#include "workflow/linuxcnc_geometry.h"

namespace hexcal::workflow {

// The `setp` lines of a HAL text: the pins it sets.
int CountHalPins(const std::string& hal_text);

// Runs `halcmd -f hal_file`; returns how many setp lines it holds. Errors
// name halcmd and quote at most the last 300 characters of its output.
StatusOr<int> PushHalFile(const std::string& halcmd, const std::string& hal_file);

// The lines of an INI's [JOINT_n] sections that must change when the machine
// moves from robot `running` to robot `calibrated`: HOME and HOME_OFFSET
// shift by (l_calibrated − l_running) × scale, the leg's reading at the home
// switch being unchanged. Empty when no offset moved by more than 1e-9.
std::string HomeOffsetShifts(const Robot& running, const Robot& calibrated, MachineUnit unit);

}  // namespace hexcal::workflow

// halcmd for loading a robot's geometry into a running LinuxCNC (`hexcal
// export --format linuxcnc-hal --push`, docs/acquisition.md): `setp` and
// `getp` lines run through `halcmd -f FILE`. genhexkins reads its pins every
// servo cycle, so the change acts at once: the world pose is held and the
// joints step (../shared/devices.md). The offsets l are not pins: they are the
// joints' home positions in the machine's INI, so they change only with the
// INI and homing again (HomeShifts says by how much, devices/linuxcnc_ini.h
// changes the INI, devices/linuxcnc_push.h does all of it on a live machine).
//
// halcmd must reach the running machine's HAL: as root, with the same
// RTAPI_UID and RTAPI_FIFO_PATH as the machine (scripts/linuxcnc-sim.sh env).
//
//   StatusOr<std::string> ran = RunHalText("halcmd", GenhexkinsHal(robot, MachineUnit::kMillimetre));
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/robot.h"
#include "core/status.h"
#include "devices/linuxcnc_geometry.h"

namespace hexcal::workflow {

// Runs `halcmd -f` on `hal_text` (from a private temporary file): its
// output. Errors name halcmd and quote at most the last 300 characters of
// its output.
StatusOr<std::string> RunHalText(const std::string& halcmd, const std::string& hal_text);

// The values of HAL pins now (`getp` through one halcmd run), in order.
// halcmd prints float pins with 7 significant digits.
StatusOr<std::vector<double>> ReadHalPins(const std::string& halcmd, const std::vector<std::string>& pins);

// An anchor point or offset l of the calibrated robot may differ from the
// running one's by this share of the robot's size at most: more is another
// robot, or a file in another length unit.
constexpr double kSameMachineShare = 0.1;

// How far each joint's home moves (machine units) when the machine goes from
// robot `running` to robot `calibrated`: l_calibrated − l_running, each robot
// converted from its own length unit, so that the leg's reading at the home
// switch is unchanged. Bad input naming the leg when the two robots are not
// the same machine (kSameMachineShare).
StatusOr<std::array<double, 6>> HomeShifts(const Robot& running, const Robot& calibrated, MachineUnit unit);

}  // namespace hexcal::workflow

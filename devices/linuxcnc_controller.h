// The `linuxcnc://HOST:PORT` controller: a LinuxCNC hexapod (genhexkins)
// driven through linuxcncrsh, LinuxCNC's text protocol over TCP
// (docs/acquisition.md, "A real LinuxCNC machine"; ../shared/devices.md).
//
// Opening: `hello EMC hexcal 1.0`, `set echo off`, `set verbose on` (without
// it `set` commands send no acknowledgement), `set enable EMCTOO`, the units
// check (`get user_linear_units` mm or inch, `get user_angular_units` deg),
// `set estop off`, `set machine on`, homing when a joint is not homed
// (`set mode manual`, `set home -1`, polling `get joint_homed`), `set mode mdi`,
// and the machine's old error messages read away.
//
// MoveTo: `set mdi G21 G90 G53 G0 X.. Y.. Z.. A.. B.. C..` (G20 on an inch
// machine): machine coordinates (G53: no work offset applies), the pose of
// devices/linuxcnc_geometry.h. The pose is first checked against the
// robot's workspace (a pose out of it is bad input naming the limit).
// WaitSettled: polls `get error` (a message fails the move, naming it),
// `get program_status` until IDLE, `get abs_cmd_pos` until it is the
// commanded pose and `get joint_pos` until the joints are still, then waits
// the settle time. ReadLegs: `get joint_pos`,
// joint − l in the robot unit.
//
//   StatusOr<LinuxCncAddress> address = ParseLinuxCncUrl("linuxcnc://127.0.0.1:5007");
//   StatusOr<std::unique_ptr<Controller>> machine = OpenLinuxCncController(*address, robot);
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "core/robot.h"
#include "core/status.h"
#include "devices/controller.h"

namespace hexcal::workflow {

struct LinuxCncAddress {
  std::string host;  // a name, an IPv4 address or an IPv6 address without brackets
  int port = 5007;
};
// "linuxcnc://HOST:PORT" (IPv6 as [ADDRESS]:PORT). Errors name the URL.
StatusOr<LinuxCncAddress> ParseLinuxCncUrl(const std::string& url);

struct LinuxCncOptions {
  std::chrono::milliseconds connect_timeout{5000};  // TCP connect
  std::chrono::milliseconds reply_timeout{5000};    // each command's reply
  double motion_timeout_seconds = 120;              // a move, or homing, must end within this, seconds
  // A move that was accepted but has not started (program idle, platform
  // elsewhere) for this long has failed, seconds.
  double idle_grace_seconds = 2;
  std::chrono::milliseconds poll_interval{20};  // between status polls
  // In position: |abs_cmd_pos − target| and the joints' change between two polls, machine unit and degrees.
  double position_tolerance = 1e-4;
  std::string connect_password = "EMC";    // linuxcncrsh --connectpw
  std::string enable_password = "EMCTOO";  // linuxcncrsh --enablepw

  bool IsValid(std::string* error) const;
};

// Connects, checks the units, powers the machine on, homes it if needed and
// enters MDI mode. `robot` is the session's nominal robot: the machine's
// genhexkins geometry must be its (hexcal export --format linuxcnc-hal).
StatusOr<std::unique_ptr<Controller>> OpenLinuxCncController(const LinuxCncAddress& address, const Robot& robot,
                                                             const LinuxCncOptions& options = {});

// Homes every joint of a `linuxcnc://` controller again, as after new joint
// homes were set (devices/linuxcnc_push.h): `set mode manual`,
// `set teleop_enable off` (homing needs joint mode), `set home -1`, then
// polls until every joint is homed and at `joints` (its new HOME, machine
// units) within `tolerance`, and `set mode mdi`. A controller of another kind
// is bad input.
Status RehomeLinuxCnc(Controller& controller, const Vector6d& joints, double tolerance);

}  // namespace hexcal::workflow

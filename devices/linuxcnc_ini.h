// The parts of a LinuxCNC machine's INI that loading a calibration changes
// (`hexcal export --push`, docs/acquisition.md, "Loading a calibration into
// LinuxCNC"): each [JOINT_n]'s HOME, HOME_OFFSET, MIN_LIMIT and MAX_LIMIT.
// A genhexkins joint is a full leg length L + l (devices/linuxcnc_geometry.h),
// so when a calibration moves the offset l of a leg by Δ, the joint's
// position at the home switch (HOME_OFFSET), its home (HOME) and its limits
// all move by Δ: the switch and the end stops are where they were, on the
// leg, and their readings L are unchanged.
//
//   StatusOr<MachineIni> ini = ParseMachineIni(text);
//   std::string patched = ShiftedIniText(*ini, {0.01, 0, 0, 0, 0, -0.02});  // mm
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/status.h"
#include "devices/linuxcnc_geometry.h"

namespace hexcal::workflow {

// The four values of one [JOINT_n] section, machine units.
struct IniJoint {
  double home = 0, home_offset = 0, min_limit = 0, max_limit = 0;
};

struct MachineIni {
  std::string text;  // the file as read, to be patched
  MachineUnit unit = MachineUnit::kMillimetre;  // [TRAJ] LINEAR_UNITS
  std::array<IniJoint, 6> joints;              // [JOINT_0] .. [JOINT_5]
  std::vector<std::string> hal_files;          // [HAL] HALFILE values, in order
};

// Parses an INI's text. Bad input names the section and key: a missing
// [TRAJ] LINEAR_UNITS or joint value, a value that is not a decimal number,
// a key given twice in a section (LinuxCNC would take the first: the patch
// could change the other), fewer than six joints.
StatusOr<MachineIni> ParseMachineIni(const std::string& text);

// The INI's text with each joint's four values moved by shifts[n] (machine
// units), written at full precision; every other byte as it was.
std::string ShiftedIniText(const MachineIni& ini, const std::array<double, 6>& shifts);

// The lines of that change, for the operator: "[JOINT_0] HOME 678.1 -> 678.2".
std::string IniChangeText(const MachineIni& ini, const std::array<double, 6>& shifts);

}  // namespace hexcal::workflow

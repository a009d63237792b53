// Leg readings in another length unit than the robot's: mm readings for a cm
// robot are ten times too long, and forward kinematics or a calibration of
// them fails far from the cause ("did not converge") or, worse, succeeds with
// the parameters of another robot. This check names the unit instead.
//
//   if (Status s = CheckReadingsUnit(robot, rows, "measurement"); !s.ok()) return s;
//   // "readings look like mm, the robot 'inria-left-hand' is in cm: ..."
#pragma once

#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

// Readings further than this many stroke lengths beyond either end of the
// stroke are "far outside" it: not noise, not a robot slightly out of range.
constexpr double kFarOutsideStrokes = 1.0;

// An error (bad input) when at least half of the readings are far outside
// their legs' strokes (one wild reading is not a unit) and every reading, converted from another length unit (mm, cm,
// m) to the robot's, lies within the strokes (a quarter stroke of slack): the message names both units and the first
// reading at fault. `row_label` names a row in the message ("measurement" gives "measurement 3: L2 = ..."); empty for a
// single set of readings. OK otherwise, also for readings far out that no
// unit explains (the caller's own checks report those).
Status CheckReadingsUnit(const Robot& robot, const std::vector<LegReadings>& rows, const std::string& row_label);

}  // namespace hexcal

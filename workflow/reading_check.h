// Readings a controller reports, checked before anything is recorded
// (issue 33; docs/acquisition.md, "Readings that are plausible or refused").
// A controller that reports 1e12, a leg at −50 cm, inch-scaled joints on a mm
// robot or the joints of another pose while "in position" must not put them
// into legs.csv: each reading must lie within its leg's stroke and agree with
// the inverse kinematics of the commanded pose (the session's nominal robot,
// the model the controller drives the legs with) within
//   tolerance = max(kReadingNoiseFactor · noise.leg, kFollowingErrorFloor),
// noise.leg being the session's half-width of the reading noise. The factor
// leaves room for a noise model that is a little optimistic; the floor covers
// a settled servo's following error, which the noise model does not hold.
//
//   StatusOr<ReadingCheck> check = SessionReadingCheck("run1");
//   if (Status s = CheckReadings(*check, "pose_0007.png", pose, legs); !s.ok()) ...;  // refused
#pragma once

#include <string>

#include "core/inverse_kinematics.h"
#include "core/noise_model.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::workflow {

constexpr double kReadingNoiseFactor = 5;             // times the leg noise's half-width
constexpr double kFollowingErrorFloorMetres = 20e-6;  // 20 µm, in metres

struct ReadingCheck {
  Robot robot;           // the session's nominal robot: strokes and IK
  double tolerance = 0;  // |reading − IK(commanded pose)| allowed, robot unit
  std::string basis;     // how the tolerance was made, for messages
};

ReadingCheck MakeReadingCheck(Robot robot, const NoiseModel& noise);
// From session.yaml: its robot and its noise model.
StatusOr<ReadingCheck> SessionReadingCheck(const std::string& session_dir);

// Failed (the controller is at fault, not the user's input) naming the pose,
// the leg, the reading, the value expected and the limit; OK when plausible.
Status CheckReadings(const ReadingCheck& check, const std::string& pose_name, const Vector6d& pose,
                     const LegReadings& readings);

// Readings an operator typed or pasted (the GUI's readings table and its
// by-hand capture dialog; issue 35): each finite and within its leg's stroke,
// with the same tolerance. Not compared with the IK of a commanded pose: a
// robot moved by hand is only near it, and an image loaded from a folder has
// none. An error (bad input) naming `where` ("view_0003.png", "pasted line
// 2"), the leg, the value and the stroke; OK when plausible.
Status CheckTypedReading(const ReadingCheck& check, const std::string& where, int leg, double value);
Status CheckTypedReadings(const ReadingCheck& check, const std::string& where, const LegReadings& readings);

}  // namespace hexcal::workflow

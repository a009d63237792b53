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

#include <optional>
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

// Readings an operator types, pastes or imports (the GUI's readings table,
// its by-hand capture dialog and Import; issue 35) come from a person, not a
// servo: they are held to a generous tolerance, per leg
//   TypedTolerance = max(kTypedReadingStrokeShare · (stroke_max − stroke_min), tolerance)
// (10 % of the stroke: 0.35 cm on the INRIA robot's 3.5 cm). An uncalibrated
// robot reads within it of its nominal model (the demo's hidden robot within
// 3 % of the stroke), and so does a robot moved by hand to the lengths shown;
// a slipped digit, a reading in another unit, swapped legs or another pose's
// row do not. Each reading must be finite and within the stroke widened by
// it, and, when the image was captured at a commanded pose (the Acquire
// step's; legs.csv's commanded columns), within it of the nominal IK of that
// pose. An image loaded from a folder has no commanded pose: the stroke only.
constexpr double kTypedReadingStrokeShare = 0.1;
double TypedTolerance(const ReadingCheck& check, int leg);

// An error (bad input) naming `where` ("view_0003.png", "pasted line 2"),
// the leg, the value and what it broke (the stroke, or the commanded pose's
// IK length and the tolerance); OK when plausible.
Status CheckTypedReading(const ReadingCheck& check, const std::string& where, int leg, double value,
                         const std::optional<Vector6d>& commanded = std::nullopt);
Status CheckTypedReadings(const ReadingCheck& check, const std::string& where, const LegReadings& readings,
                          const std::optional<Vector6d>& commanded = std::nullopt);

}  // namespace hexcal::workflow

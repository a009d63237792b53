// Moves a straight-line controller can make: waypoints between two platform
// poses such that every straight move between them keeps every leg within its
// stroke and the pose within the robot's other limits (docs/acquisition.md,
// "Moves the machine can make").
//
// A controller such as LinuxCNC's genhexkins moves the platform along a
// straight line in "motion space" m = [x, y, z, A, B, C]: the position (robot
// unit) and the xyz (roll-pitch-yaw) Euler angles in degrees. A leg's length
// is not linear along such a line, so a leg can pass its stroke between two
// poses that are both within it. The strokes are a box in leg space, and a box
// is convex: the straight line in leg space between the two poses' readings,
// bent a little towards the middle of the strokes M (StraightMoveOptions::bulge),
//   L(s) = ℓ(s) + bulge·4s(1 − s)·(M − ℓ(s)),  ℓ(s) = (1 − s)·L_from + s·L_to,
// stays inside it. Forward kinematics by continuation along L(s) (local FK
// from the previous point, so it stays in one assembly mode) gives platform
// poses on that line; between close enough ones the straight motion-space
// segment stays within the stroke too. Each segment is checked at dense
// samples and split at its middle s where it does not hold; the waypoints are
// then the fewest continuation points whose segments all hold.
//
//   StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot, here, target);
//   for (const Vector6d& m : *moves) send_g0(m);  // the last one is `target`
#pragma once

#include <string>
#include <vector>

#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

struct StraightMoveOptions {
  // A sample may pass a stroke end by this fraction of the stroke (3.5 µm on
  // INRIA's 3.5 cm): the chord's bow between two waypoints is never exactly
  // zero where the leg-space line ends on the stroke (a boundary pose). Far
  // inside a machine's end stops (linuxcnc-sim.sh sets them 2 % outside) and
  // below the sensors' noise. Unitless.
  double stroke_tolerance = 1e-4;
  // The leg-space path is bent towards the middle of the strokes by this
  // fraction of the way at its midpoint (4s(1 − s) along it): a margin from
  // the stroke ends where both poses have a leg at the same end (boundary
  // poses), which the straight leg-space line would run along, needing a
  // waypoint every few hundredths of the way. Unitless, in [0, 1).
  double bulge = 0.05;
  int samples_per_segment = 256;  // checked points per straight segment (ends included)
  int continuation_steps = 32;    // FK points along L(s) before any split
  int max_split_depth = 12;       // a segment is halved at most this often (2^-12 of the path)
  // Poses to go through, in turn, when the leg-space line from `from` to `to`
  // does not work (FK does not follow it, another constraint breaks): each is
  // tried as `from → via → to` (motion space, as `from`).
  std::vector<Vector6d> vias;
};

// m of a pose: position and xyz Euler angles in degrees.
Vector6d MotionVectorFromPose(const Pose& pose);
Pose PoseFromMotionVector(const Vector6d& motion);

// Whether every sample of the straight segment a → b keeps each leg within
// [stroke_min − t, stroke_max + t] (t: the tolerance, widened to include a
// leg's reading at `path_start` when that is outside, so that a platform left
// beyond a stroke end can move back) and the other limits of the robot (joint
// angles, leg distance, assembly mode; not the pose box) satisfied. On false,
// `why` names the limit, the sample's pose and by how much.
bool StraightSegmentHolds(const Robot& robot, const Vector6d& a, const Vector6d& b, const Vector6d& path_start,
                          const StraightMoveOptions& options, std::string* why = nullptr);

// The motion-space waypoints after `from` up to and including `to` (exactly
// `to`'s numbers), each straight segment holding. `from` may be outside the
// strokes (see above); `to` must be within the robot's workspace (the caller
// checks). An error (bad input) says why no path was found, naming the pose
// and the limit that broke.
StatusOr<std::vector<Vector6d>> PlanStraightMoves(const Robot& robot, const Vector6d& from, const Vector6d& to,
                                                  const StraightMoveOptions& options = {});

}  // namespace hexcal

#include "core/straight_moves.h"

#include <algorithm>
#include <cmath>

#include "core/constraints.h"
#include "core/csv.h"
#include "core/forward_kinematics.h"
#include "core/inverse_kinematics.h"

namespace hexcal {
namespace {

// Where the path starts: a platform left beyond a limit may move back to it,
// so the limits it already breaks are held to their value there.
struct PathStart {
  LegReadings readings;
  std::vector<double> margins;  // ConstraintMargins without the pose box
};

PathStart StartOf(const Robot& robot, const Vector6d& from) {
  const Pose pose = PoseFromMotionVector(from);
  return {InverseKinematics(robot, pose), ConstraintMargins(robot, pose, /*include_box=*/false)};
}

std::string MotionText(const Vector6d& m) {
  std::string text = "(";
  for (int k = 0; k < 6; ++k) text += FormatNumber(std::round(m[k] * 1e6) / 1e6) + (k < 5 ? ", " : ")");
  return text;
}

std::string Rounded(double value) { return FormatNumber(std::round(value * 1e6) / 1e6); }

bool SampleHolds(const Robot& robot, const Vector6d& m, const PathStart& start, const StraightMoveOptions& options,
                 std::string* why) {
  const Pose pose = PoseFromMotionVector(m);
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const double reading = LegVector(leg, pose).norm() - leg.offset;
    const double slack = options.stroke_tolerance * (leg.stroke_max - leg.stroke_min);
    const double low = std::min(leg.stroke_min, start.readings[i]) - slack;
    const double high = std::max(leg.stroke_max, start.readings[i]) + slack;
    if (reading >= low && reading <= high) continue;
    if (why)
      *why = "leg " + std::to_string(i + 1) + " would read " + Rounded(reading) + " at " + MotionText(m) +
             ", outside its stroke [" + FormatNumber(leg.stroke_min) + ", " + FormatNumber(leg.stroke_max) + "]";
    return false;
  }
  // ConstraintMargins lists each leg's stroke min, stroke max and joint angles
  // (when limited) first: the strokes are checked above, with their tolerance.
  const size_t per_leg = 2 + (robot.limits.base_joint_max_deg ? 1 : 0) + (robot.limits.platform_joint_max_deg ? 1 : 0);
  const std::vector<double> margins = ConstraintMargins(robot, pose, /*include_box=*/false);
  for (size_t k = 0; k < margins.size(); ++k) {
    if (k < per_leg * kNumLegs && k % per_leg < 2) continue;
    const double floor = std::min(0.0, k < start.margins.size() ? start.margins[k] : 0.0) - kFeasibilityTolerance;
    if (margins[k] >= floor) continue;
    if (why) {
      const ConstraintReport report = EvaluateConstraints(robot, pose);  // the same order, with labels
      *why = report.margins[k].label + " broken by " + Rounded(-margins[k]) + " at " + MotionText(m);
    }
    return false;
  }
  return true;
}

bool SegmentHolds(const Robot& robot, const Vector6d& a, const Vector6d& b, const PathStart& start,
                  const StraightMoveOptions& options, std::string* why) {
  const int n = std::max(1, options.samples_per_segment - 1);
  for (int k = 0; k <= n; ++k)
    if (!SampleHolds(robot, a + (static_cast<double>(k) / n) * (b - a), start, options, why)) return false;
  return true;
}

// The leg-space path: the straight line from the start's readings to the
// target's, bent towards the middle of the strokes by
// bulge · 4s(1 − s) of the way. A convex combination of points inside the
// box stays inside it; the bend keeps legs that sit on the same stroke end at
// both poses off that end between them, where the straight line would run
// along it and every chord's bow would need a split.
struct LegPath {
  LegReadings from, to, middle;
  double bulge = 0;
  LegReadings At(double s) const {
    const LegReadings line = (1 - s) * from + s * to;
    return line + (bulge * 4 * s * (1 - s)) * (middle - line);
  }
};

LegPath MakeLegPath(const Robot& robot, const Vector6d& from, const Vector6d& to, double bulge) {
  LegPath path{InverseKinematics(robot, PoseFromMotionVector(from)), InverseKinematics(robot, PoseFromMotionVector(to)),
               LegReadings::Zero(), bulge};
  for (int i = 0; i < kNumLegs; ++i) path.middle[i] = (robot.legs[i].stroke_min + robot.legs[i].stroke_max) / 2;
  return path;
}

// A point of the continuation: s along the leg-space path, its pose and m.
struct PathPoint {
  double s = 0;
  Pose pose;
  Vector6d m = Vector6d::Zero();
};

// The pose where the legs read path.At(s), by local FK from a neighbouring
// point (so the path stays in its assembly mode); its angles are taken within
// half a turn of the neighbour's, as the controller moves through the numbers.
StatusOr<PathPoint> PointAt(const Robot& robot, const LegPath& path, double s, const PathPoint& near) {
  StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(robot, path.At(s), near.pose);
  if (!fk.ok()) return fk.status();
  PathPoint point{s, fk->pose, MotionVectorFromPose(fk->pose)};
  for (int k = 3; k < 6; ++k) point.m[k] += 360 * std::round((near.m[k] - point.m[k]) / 360);
  return point;
}

// The continuation from `from` to `to` in steps of 1/continuation_steps (a
// step FK does not follow is halved); its last point is `to` itself.
StatusOr<std::vector<PathPoint>> FollowLegPath(const Robot& robot, const LegPath& path, const Vector6d& from,
                                               const Vector6d& to, const StraightMoveOptions& options) {
  std::vector<PathPoint> points{{0, PoseFromMotionVector(from), from}};
  const double step = 1.0 / std::max(1, options.continuation_steps);
  const double min_step = step / std::ldexp(1.0, options.max_split_depth);
  for (double h = step; points.back().s < 1;) {
    const double s = std::min(1.0, points.back().s + h);
    StatusOr<PathPoint> next = PointAt(robot, path, s, points.back());
    if (next.ok()) {
      points.push_back(*next);
      h = step;
    } else if ((h /= 2) < min_step) {
      return Status::BadInput("forward kinematics does not follow the legs' path at " + Rounded(points.back().s) +
                              " of the way: " + next.status().message());
    }
  }
  const Pose target = PoseFromMotionVector(to);
  const Pose& end = points.back().pose;
  if ((end.position - target.position).norm() > 1e-6 * (1 + target.position.norm()) ||
      RotationDistance(end.rotation, target.rotation) > 1e-6)
    return Status::BadInput("the legs' path leads to another assembly mode than the pose " + MotionText(to));
  points.back().m = to;
  return points;
}

// Waypoints after a, up to b, splitting at the middle s while a segment fails.
Status Split(const Robot& robot, const LegPath& path, const PathPoint& a, const PathPoint& b, const PathStart& start,
             const StraightMoveOptions& options, int depth, std::vector<Vector6d>* out) {
  std::string why;
  if (SegmentHolds(robot, a.m, b.m, start, options, &why)) {
    out->push_back(b.m);
    return Status::Ok();
  }
  if (depth >= options.max_split_depth) return Status::BadInput(why);
  StatusOr<PathPoint> middle = PointAt(robot, path, (a.s + b.s) / 2, a);
  if (!middle.ok()) return Status::BadInput(why + " (and FK between: " + middle.status().message() + ")");
  if (Status s = Split(robot, path, a, *middle, start, options, depth + 1, out); !s.ok()) return s;
  return Split(robot, path, *middle, b, start, options, depth + 1, out);
}

// From each point, the farthest later one a single straight move reaches.
StatusOr<std::vector<Vector6d>> AlongLegPath(const Robot& robot, const Vector6d& from, const Vector6d& to,
                                             const PathStart& start, const StraightMoveOptions& options) {
  const LegPath path = MakeLegPath(robot, from, to, options.bulge);
  StatusOr<std::vector<PathPoint>> points = FollowLegPath(robot, path, from, to, options);
  if (!points.ok()) return points.status();
  std::vector<Vector6d> moves;
  const size_t last = points->size() - 1;
  for (size_t i = 0; i < last;) {
    size_t j = last;
    while (j > i + 1 && !SegmentHolds(robot, (*points)[i].m, (*points)[j].m, start, options, nullptr)) --j;
    if (j == i + 1) {
      Status split = Split(robot, path, (*points)[i], (*points)[j], start, options, 0, &moves);
      if (!split.ok()) return split;
    } else {
      moves.push_back((*points)[j].m);
    }
    i = j;
  }
  moves.back() = to;
  return moves;
}

}  // namespace

Vector6d MotionVectorFromPose(const Pose& pose) { return VectorFromPose(pose, EulerConvention::kXYZ); }

Pose PoseFromMotionVector(const Vector6d& motion) { return PoseFromVector(motion, EulerConvention::kXYZ); }

bool StraightSegmentHolds(const Robot& robot, const Vector6d& a, const Vector6d& b, const Vector6d& path_start,
                          const StraightMoveOptions& options, std::string* why) {
  return SegmentHolds(robot, a, b, StartOf(robot, path_start), options, why);
}

StatusOr<std::vector<Vector6d>> PlanStraightMoves(const Robot& robot, const Vector6d& from, const Vector6d& to,
                                                  const StraightMoveOptions& options) {
  const PathStart start = StartOf(robot, from);
  if (SegmentHolds(robot, from, to, start, options, nullptr)) return std::vector<Vector6d>{to};
  StatusOr<std::vector<Vector6d>> direct = AlongLegPath(robot, from, to, start, options);
  if (direct.ok()) return direct;
  for (const Vector6d& via : options.vias) {
    StatusOr<std::vector<Vector6d>> first = AlongLegPath(robot, from, via, start, options);
    if (!first.ok()) continue;
    StatusOr<std::vector<Vector6d>> second = AlongLegPath(robot, via, to, start, options);
    if (!second.ok()) continue;
    first->insert(first->end(), second->begin(), second->end());
    return first;
  }
  return Status::BadInput("no straight moves from " + MotionText(from) + " to " + MotionText(to) +
                          " keep within the robot's limits: " + direct.status().message());
}

}  // namespace hexcal

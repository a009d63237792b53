#include "core/constraints.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/inverse_kinematics.h"

namespace hexcal {
namespace {

double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return RadToDeg(std::atan2(u.cross(v).norm(), u.dot(v)));
}

const char* kPoseNames[6] = {"x", "y", "z", "q1", "q2", "q3"};

// det of a 6x6 matrix by Gaussian elimination with partial pivoting: several
// times cheaper than Eigen's general LU at this size, and the planner's polish
// evaluates margins some hundred thousand times per plan.
double Determinant6(Eigen::Matrix<double, 6, 6> m) {
  double det = 1;
  for (int k = 0; k < 6; ++k) {
    int pivot = k;
    for (int r = k + 1; r < 6; ++r) {
      if (std::abs(m(r, k)) > std::abs(m(pivot, k))) pivot = r;
    }
    if (m(pivot, k) == 0) return 0;
    if (pivot != k) {
      m.row(k).swap(m.row(pivot));
      det = -det;
    }
    det *= m(k, k);
    for (int r = k + 1; r < 6; ++r) {
      const double factor = m(r, k) / m(k, k);
      for (int c = k + 1; c < 6; ++c) m(r, c) -= factor * m(k, c);
    }
  }
  return det;
}

// det J_IK at the mode's pose, kept per thread for the last geometry asked
// (a and b of every leg, the mode's pose and the Euler convention are the key).
double ModePoseDeterminant(const Robot& robot, const AssemblyMode& mode) {
  constexpr size_t kKeySize = kNumLegs * 6 + 6 + 1;
  thread_local std::array<double, kKeySize> cached_key{};
  thread_local double cached = std::nan("");
  std::array<double, kKeySize> key;
  size_t k = 0;
  for (const Leg& leg : robot.legs) {
    for (int c = 0; c < 3; ++c) key[k++] = leg.a_in_base[c];
    for (int c = 0; c < 3; ++c) key[k++] = leg.b_in_platform[c];
  }
  for (int c = 0; c < 6; ++c) key[k++] = mode.pose[c];
  key[k] = static_cast<double>(robot.euler);
  if (key != cached_key || std::isnan(cached)) {
    cached = Determinant6(InverseKinematicsJacobian(robot, robot.PoseFromVector(mode.pose)));
    cached_key = key;
  }
  return cached;
}

// The sign of det J_IK marks the assembly mode (section 5.3): it changes only
// across a parallel singularity, where det J_IK is 0. The ratio to its value at
// the mode's pose also says how far from one a pose is (docs/robot-file.md).
double AssemblyModeMargin(const Robot& robot, const AssemblyMode& mode, const Pose& pose) {
  return Determinant6(InverseKinematicsJacobian(robot, pose)) / ModePoseDeterminant(robot, mode) -
         mode.min_det_ratio;
}

// Calls visit(kind, leg_or_index, other_index, margin) for every constraint
// (the pose box's only with include_box: it costs three inverse trigonometric calls).
template <typename Visit>
void VisitConstraints(const Robot& robot, const Pose& pose, bool include_box, Visit&& visit) {
  std::array<Eigen::Vector3d, kNumLegs> leg_top;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const Eigen::Vector3d v = LegVector(leg, pose);
    const double reading = v.norm() - leg.offset;
    visit(ConstraintKind::kStrokeMin, i, -1, reading - leg.stroke_min);
    visit(ConstraintKind::kStrokeMax, i, -1, leg.stroke_max - reading);
    if (robot.limits.base_joint_max_deg) {
      visit(ConstraintKind::kBaseJoint, i, -1,
            *robot.limits.base_joint_max_deg - AngleDeg(v, Eigen::Vector3d::UnitZ()));
    }
    if (robot.limits.platform_joint_max_deg) {
      visit(ConstraintKind::kPlatformJoint, i, -1,
            *robot.limits.platform_joint_max_deg - AngleDeg(v, pose.rotation.col(2)));
    }
    leg_top[i] = leg.a_in_base + v;
  }
  if (robot.limits.leg_min_distance) {
    for (int i = 0; i < kNumLegs; ++i) {
      for (int j = i + 1; j < kNumLegs; ++j) {
        // Neighbouring legs sharing a joint (distance 0 by design) are skipped.
        const bool share_base =
            (robot.legs[i].a_in_base - robot.legs[j].a_in_base).norm() <= *robot.limits.leg_min_distance;
        const bool share_top =
            (robot.legs[i].b_in_platform - robot.legs[j].b_in_platform).norm() <= *robot.limits.leg_min_distance;
        if (share_base || share_top) continue;
        const double d = SegmentDistance(robot.legs[i].a_in_base, leg_top[i], robot.legs[j].a_in_base, leg_top[j]);
        visit(ConstraintKind::kLegDistance, i, j, d - *robot.limits.leg_min_distance);
      }
    }
  }
  if (robot.limits.assembly_mode) {
    visit(ConstraintKind::kAssemblyMode, -1, -1, AssemblyModeMargin(robot, *robot.limits.assembly_mode, pose));
  }
  if (include_box && robot.limits.pose_box) {
    const Vector6d v = robot.VectorFromPose(pose);
    for (int k = 0; k < 6; ++k) {
      const auto& range = robot.limits.pose_box->bounds[k];
      if (!range) continue;
      visit(ConstraintKind::kPoseBox, k, 0, v[k] - range->min);
      visit(ConstraintKind::kPoseBox, k, 1, range->max - v[k]);
    }
  }
}

std::string Label(ConstraintKind kind, int i, int j) {
  switch (kind) {
    case ConstraintKind::kStrokeMin:
      return "stroke min L" + std::to_string(i + 1);
    case ConstraintKind::kStrokeMax:
      return "stroke max L" + std::to_string(i + 1);
    case ConstraintKind::kBaseJoint:
      return "base joint " + std::to_string(i + 1);
    case ConstraintKind::kPlatformJoint:
      return "platform joint " + std::to_string(i + 1);
    case ConstraintKind::kLegDistance:
      return "leg distance " + std::to_string(i + 1) + "-" + std::to_string(j + 1);
    case ConstraintKind::kAssemblyMode:
      return "assembly mode";
    case ConstraintKind::kPoseBox:
      return std::string("pose box ") + kPoseNames[i] + (j == 0 ? " min" : " max");
  }
  return "?";
}

}  // namespace

ConstraintReport EvaluateConstraints(const Robot& robot, const Pose& pose) {
  ConstraintReport report;
  report.worst_margin = std::numeric_limits<double>::infinity();
  VisitConstraints(robot, pose, /*include_box=*/true, [&](ConstraintKind kind, int i, int j, double margin) {
    report.margins.push_back({kind, Label(kind, i, j), margin});
    if (!(margin >= report.worst_margin)) {  // also catches NaN
      report.worst_margin = margin;
      report.worst_label = report.margins.back().label;
    }
  });
  report.feasible = report.worst_margin >= -kFeasibilityTolerance;
  return report;
}

bool WithinStroke(const Leg& leg, double reading) {
  return reading >= leg.stroke_min - kFeasibilityTolerance && reading <= leg.stroke_max + kFeasibilityTolerance;
}

bool IsFeasible(const Robot& robot, const Pose& pose) {
  // Strokes first: in a pose box most rejected poses fail here, at the cost of IK.
  for (const Leg& leg : robot.legs) {
    if (!WithinStroke(leg, LegVector(leg, pose).norm() - leg.offset)) return false;
  }
  bool feasible = true;
  VisitConstraints(robot, pose, /*include_box=*/true, [&](ConstraintKind, int, int, double margin) {
    if (!(margin >= -kFeasibilityTolerance)) feasible = false;
  });
  return feasible;
}

std::vector<double> ConstraintMargins(const Robot& robot, const Pose& pose, bool include_box) {
  std::vector<double> margins;
  // 4 per leg, 15 leg pairs, the assembly mode, 12 box bounds: one allocation (optimisers call this often).
  margins.reserve(64);
  VisitConstraints(robot, pose, include_box,
                   [&](ConstraintKind, int, int, double margin) { margins.push_back(margin); });
  return margins;
}

double SegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                       const Eigen::Vector3d& q1) {
  // Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9).
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double eps = 1e-300;
  double s = 0, t = 0;
  if (a <= eps && e <= eps) return r.norm();
  if (a <= eps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > eps ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p0 + d1 * s) - (q0 + d2 * t)).norm();
}

}  // namespace hexcal

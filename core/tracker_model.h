// A laser tracker as the planner sees it (docs/planner.md, "Planning for a
// laser tracker"): how well it measures each reflector at a pose, and whether
// it sees them at all.
//
// Noise. Each coordinate of reflector k is measured with σ_k: point_sigma
// (law `constant`), or σ_k = σ0 + k·d_k (law `linear`, a tracker's usual
// specification, e.g. 15 µm + 6 µm/m) with d_k the distance from the tracker
// to the reflector. The platform's pose at a candidate pose is then known with
// the covariance the weighted point fit states for those σ_k at the
// reflectors' positions there (core/point_fit.h, PointPoseCovariance): near
// poses and a wide spread of reflectors are better measured.
//
// Line of sight (with the tracker's position). A reflector at p with normal n
// is seen from the tracker at t when
//   1. the direction t − p is within `acceptance_deg` of n (an SMR's cone);
//   2. the segment p→t does not cross the platform: a disc in the plane of the
//      platform anchors (z = their mean z in the platform frame), centred on
//      their centroid, of their largest radius;
//   3. the segment p→t passes no leg closer than `leg_radius` (each leg the
//      cylinder about the segment a_i → P + R b_i; SegmentDistance of
//      core/constraints.h).
// A pose is admissible when every reflector is seen: the planned covariance
// assumes all of them are measured.
//
//   StatusOr<TrackerModel> tracker = MakeTrackerModel(robot, reflectors_in_platform, point_sigma, settings);
//   Matrix6d covariance = TrackerPoseCovariance(*tracker, robot, pose);  // of robot.VectorFromPose(pose)
//   std::vector<double> margins = LineOfSightMargins(*tracker, robot, pose);  // all >= 0: every reflector seen
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/option_spec.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

enum class PointSigmaLaw { kConstant, kLinear };

// session.yaml's `tracker:` section (docs/session.md), robot unit.
struct TrackerSettings {
  std::optional<Eigen::Vector3d> position;  // the tracker's head in the base frame; enables the line of sight
  PointSigmaLaw sigma_law = PointSigmaLaw::kConstant;  // kLinear needs position, sigma0, sigma_per_distance
  double sigma0 = 0;              // σ at distance 0 (robot unit), law linear
  double sigma_per_distance = 0;  // growth of σ per unit of distance (unit per unit: 6 µm/m = 6e-6), law linear
  double acceptance_deg = 30;     // half-angle of a reflector's acceptance cone
  Eigen::Vector3d reflector_normal = Eigen::Vector3d::UnitZ();  // reflector frame (the platform's until registered)
  double leg_radius = 0;          // the legs' radius (robot unit): 0 takes them as lines

  // Ranges of the scalar keys (TrackerSettingsOptions) and the law's needs;
  // `error` names the key.
  bool IsValid(std::string* error) const;
};

// sigma_law, sigma0, sigma_per_distance, acceptance_deg, leg_radius:
// described once, for session.yaml and the docs.
const OptionTable<TrackerSettings>& TrackerSettingsOptions();

// The planner's tracker: the reflectors in the platform frame, the σ law,
// the line-of-sight geometry.
struct TrackerModel {
  std::vector<Eigen::Vector3d> reflectors;  // platform frame, robot unit
  double point_sigma = 0;                   // law constant: σ of every coordinate
  TrackerSettings settings;
  Eigen::Vector3d normal_in_platform = Eigen::Vector3d::UnitZ();  // unit
  // The platform disc (platform frame): centre and radius.
  Eigen::Vector3d disc_centre = Eigen::Vector3d::Zero();
  double disc_radius = 0;
};

// Bad input when the reflectors are fewer than 3 or on one line, the
// settings out of range, or point_sigma not positive. `platform_from_reflectors`
// maps the reflector file's frame (and the normal) to the platform's.
StatusOr<TrackerModel> MakeTrackerModel(const Robot& robot, const std::vector<Eigen::Vector3d>& reflectors,
                                        double point_sigma, const TrackerSettings& settings,
                                        const Pose& platform_from_reflectors = Pose{});

// σ of each coordinate of a point at `distance` from the tracker.
double PointSigmaAt(const TrackerModel& tracker, double distance);
// σ of each reflector at `base_from_platform` (the law's distance from the
// tracker; point_sigma without a position).
std::vector<double> ReflectorSigmas(const TrackerModel& tracker, const Pose& base_from_platform);
// The covariance of robot.VectorFromPose(base_from_platform) measured by the
// tracker (robot unit², degrees²).
Matrix6d TrackerPoseCovariance(const TrackerModel& tracker, const Robot& robot, const Pose& base_from_platform);

// One reflector's sight margins (≥ 0: seen), for hand-checked geometry:
// {acceptance_deg − angle(n, t − p) in degrees, the disc's (length), the legs' (length)}.
struct SightScene {
  Eigen::Vector3d tracker;                  // t
  double acceptance_deg = 30;
  Eigen::Vector3d disc_centre, disc_normal;  // disc_normal unit
  double disc_radius = 0;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> legs;  // segment ends
  double leg_radius = 0;
};
std::array<double, 3> ReflectorSightMargins(const SightScene& scene, const Eigen::Vector3d& reflector,
                                            const Eigen::Vector3d& normal);
// Three margins per reflector (ReflectorSightMargins) at the pose; empty
// without a tracker position.
std::vector<double> LineOfSightMargins(const TrackerModel& tracker, const Robot& robot, const Pose& base_from_platform);

}  // namespace hexcal

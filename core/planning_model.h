// What the planner needs to know about a pose: its identification rows and
// whether it may be measured.
//
// Rows are the nominal Jacobian rows of eq. 5 (the reading the nominal model
// predicts), or with a noise model each row divided by the standard deviation
// of its residual (noise_model.h), so that the information matrix is the
// inverse covariance of the least-squares estimate: the planner then maximises
// precision under the actual measurement noise, not the conditioning of J_P.
//
// With a laser tracker (core/tracker_model.h) the pose noise is the tracker's
// at each pose: the rows are divided by σ(F_ij) computed with that pose's
// covariance (the reflectors' σ grow with their distance from the tracker),
// the reading noise still the noise model's.
//
// Measurement constraints (optional, beyond the paper) keep the target
// measurable: its centre inside the camera's field of view and its normal
// within a maximum angle of the line of sight; with a tracker's position,
// every reflector in its line of sight.
#pragma once

#include <optional>
#include <vector>

#include "core/design_criteria.h"
#include "core/noise_model.h"
#include "core/status.h"
#include "core/tracker_model.h"

namespace hexcal {

struct MeasurementConstraints {
  Pose base_from_camera;          // camera looks along its +z
  Pose platform_from_target;      // target normal is its +z
  double half_fov_x_deg = 30;     // half the horizontal field of view
  double half_fov_y_deg = 25;     // half the vertical field of view
  double max_view_angle_deg = 60; // between the target normal and the direction to the camera
};

struct PlanningModel {
  Robot robot;
  std::optional<NoiseModel> noise;                    // weight rows by 1/σ(F_ij)
  std::optional<MeasurementConstraints> measurement;  // camera visibility
  // A laser tracker: its per-pose covariance replaces the noise model's pose
  // terms (with `noise` set), its position adds the line of sight.
  std::optional<TrackerModel> tracker{};

  PoseRows Rows(const Vector6d& pose) const;
  // The rows of every pose, on `threads` cores (0: every core).
  CandidateRows RowsOf(const std::vector<Vector6d>& poses, int threads = 0) const;
  // Which poses are feasible (IsFeasible), on `threads` cores.
  std::vector<char> FeasibleOf(const std::vector<Vector6d>& poses, int threads = 0) const;
  // d(rows)/d(pose vector) as six 7x6 matrices (angles per degree).
  std::array<Eigen::Matrix<double, kParamsPerLeg, 6>, kNumLegs> RowJacobians(const Vector6d& pose) const;
  // Robot margins (optionally without the pose box) followed by the measurement margins.
  std::vector<double> Margins(const Vector6d& pose, bool include_box) const;
  bool IsFeasible(const Vector6d& pose) const;
  // The tracker's covariance of the pose vector at `pose` (robot unit²,
  // degrees²); none without a tracker.
  std::optional<Matrix6d> PoseCovariance(const Vector6d& pose) const;
};

// Margins of the measurement constraints: fov x, fov y, in front of the camera, view angle.
std::vector<double> MeasurementMargins(const MeasurementConstraints& constraints, const Pose& base_from_platform);

// Plan settings file (YAML): optional `noise: {position, angle_deg, leg}` and
// optional `camera: {position, rotation_deg}`, `target: {position, rotation_deg}`,
// `field_of_view_deg: [horizontal, vertical]`, `max_view_angle_deg`. docs/planner.md.
struct PlanSettings {
  std::optional<NoiseModel> noise;
  std::optional<MeasurementConstraints> measurement;
  // The `planner:` section's (key, value) entries, applied by the plan step
  // against its option table (workflow/plan_options.h).
  std::vector<std::pair<std::string, std::string>> planner;
};
StatusOr<PlanSettings> LoadPlanSettings(const std::string& path, const Robot& robot);
// The same from the file's text; `path` names it in messages.
StatusOr<PlanSettings> ParsePlanSettings(const std::string& text, const std::string& path, const Robot& robot);

}  // namespace hexcal

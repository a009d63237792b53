#include "core/planning_model.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "core/atomic_file.h"
#include "core/constraints.h"
#include "core/inverse_kinematics.h"
#include "core/noise_yaml.h"
#include "core/parallel.h"
#include "core/yaml_document.h"

namespace hexcal {

// Blocks of poses per ParallelFor item: large enough that the items cost far
// more than handing them out.
constexpr int kPoseBlock = 512;

CandidateRows PlanningModel::RowsOf(const std::vector<Vector6d>& poses, int threads) const {
  CandidateRows rows;
  rows.Resize(static_cast<int>(poses.size()));
  ParallelForBlocks(static_cast<int>(poses.size()), kPoseBlock, threads, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) rows.Set(j, Rows(poses[j]));
  });
  return rows;
}

std::vector<char> PlanningModel::FeasibleOf(const std::vector<Vector6d>& poses, int threads) const {
  std::vector<char> feasible(poses.size());
  ParallelForBlocks(static_cast<int>(poses.size()), kPoseBlock, threads, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) feasible[j] = IsFeasible(poses[j]);
  });
  return feasible;
}

namespace {

// The rows divided by their residuals' standard deviations, at a pose whose
// rotation partials are known (computed once for the six legs).
PoseRows WeightedRows(const Robot& robot, const MeasuredPose& measured, const NoiseModel& noise) {
  PoseRows rows;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    rows[i] = NominalJacobianRow(leg, measured.pose);
    const double reading = LegVector(leg, measured.pose).norm() - leg.offset;
    rows[i] /= ResidualStdDev(leg, measured, reading, noise);
  }
  return rows;
}

// The same with the pose's own covariance (the tracker's at this pose).
PoseRows TrackerWeightedRows(const Robot& robot, const Vector6d& v, const NoiseModel& noise,
                             const Matrix6d& pose_covariance) {
  const MeasuredPose measured = MeasuredPoseOf(robot, v);
  PoseRows rows;
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    rows[i] = NominalJacobianRow(leg, measured.pose);
    const double reading = LegVector(leg, measured.pose).norm() - leg.offset;
    rows[i] /= ResidualStdDev(leg, measured, reading, noise, pose_covariance);
  }
  return rows;
}

}  // namespace

std::optional<Matrix6d> PlanningModel::PoseCovariance(const Vector6d& v) const {
  if (!tracker) return std::nullopt;
  return TrackerPoseCovariance(*tracker, robot, robot.PoseFromVector(v));
}

PoseRows PlanningModel::Rows(const Vector6d& v) const {
  if (noise && tracker) return TrackerWeightedRows(robot, v, *noise, *PoseCovariance(v));
  if (noise) return WeightedRows(robot, MeasuredPoseOf(robot, v), *noise);
  PoseRows rows;
  const Pose pose = robot.PoseFromVector(v);
  for (int i = 0; i < kNumLegs; ++i) rows[i] = NominalJacobianRow(robot.legs[i], pose);
  return rows;
}

std::array<Eigen::Matrix<double, kParamsPerLeg, 6>, kNumLegs> PlanningModel::RowJacobians(const Vector6d& v) const {
  std::array<Eigen::Matrix<double, kParamsPerLeg, 6>, kNumLegs> jacobians;
  if (noise) {  // the weight 1/σ(pose) has no closed form worth keeping: central differences
    // A step in x, y or z leaves the rotation and its partials as they are:
    // computed once, they are the very values Rows(v ± h e_k) would compute.
    const MeasuredPose at = MeasuredPoseOf(robot, v);
    for (int k = 0; k < 6; ++k) {
      const double h = 1e-6 * (1 + std::abs(v[k]));
      Vector6d plus = v, minus = v;
      plus[k] += h;
      minus[k] -= h;
      PoseRows rp, rm;
      if (k < 3 && !tracker) {  // the tracker's covariance moves with the position
        MeasuredPose moved = at;
        moved.pose.position[k] = plus[k];
        rp = WeightedRows(robot, moved, *noise);
        moved.pose.position[k] = minus[k];
        rm = WeightedRows(robot, moved, *noise);
      } else {
        rp = Rows(plus), rm = Rows(minus);
      }
      for (int i = 0; i < kNumLegs; ++i) jacobians[i].col(k) = (rp[i] - rm[i]).transpose() / (2 * h);
    }
    return jacobians;
  }
  // Row = [-2v, 2 Rᵀv, -2|v|] with v = P + R b - a (eq. 5).
  const Pose pose = robot.PoseFromVector(v);
  const Eigen::Vector3d q(DegToRad(v[3]), DegToRad(v[4]), DegToRad(v[5]));
  const auto partials = RotationEulerPartials(q, robot.euler);
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const Eigen::Vector3d leg_vector = LegVector(leg, pose);
    const double length = leg_vector.norm();
    for (int k = 0; k < 6; ++k) {
      Eigen::Vector3d dv, dw;
      if (k < 3) {
        dv = Eigen::Vector3d::Unit(k);
        dw = pose.rotation.row(k).transpose();
      } else {
        const Eigen::Matrix3d dr = partials[k - 3] * DegToRad(1.0);
        dv = dr * leg.b_in_platform;
        dw = dr.transpose() * leg_vector + pose.rotation.transpose() * dv;
      }
      jacobians[i].col(k) << -2 * dv, 2 * dw, -2 * leg_vector.dot(dv) / length;
    }
  }
  return jacobians;
}

std::vector<double> MeasurementMargins(const MeasurementConstraints& c, const Pose& base_from_platform) {
  const Eigen::Vector3d target_in_base = base_from_platform * c.platform_from_target.position;
  const Eigen::Matrix3d camera_from_base = c.base_from_camera.rotation.transpose();
  const Eigen::Vector3d target_in_camera = camera_from_base * (target_in_base - c.base_from_camera.position);
  const double angle_x = RadToDeg(std::atan2(std::abs(target_in_camera.x()), target_in_camera.z()));
  const double angle_y = RadToDeg(std::atan2(std::abs(target_in_camera.y()), target_in_camera.z()));
  const Eigen::Vector3d normal = base_from_platform.rotation * c.platform_from_target.rotation.col(2);
  const Eigen::Vector3d to_camera = c.base_from_camera.position - target_in_base;
  const double view = RadToDeg(std::atan2(normal.cross(to_camera).norm(), normal.dot(to_camera)));
  return {c.half_fov_x_deg - angle_x, c.half_fov_y_deg - angle_y, target_in_camera.z(), c.max_view_angle_deg - view};
}

std::vector<double> PlanningModel::Margins(const Vector6d& v, bool include_box) const {
  const Pose pose = robot.PoseFromVector(v);
  std::vector<double> margins = ConstraintMargins(robot, pose, include_box);
  if (measurement) {
    for (double m : MeasurementMargins(*measurement, pose)) margins.push_back(m);
  }
  if (tracker) {
    for (double m : LineOfSightMargins(*tracker, robot, pose)) margins.push_back(m);
  }
  return margins;
}

bool PlanningModel::IsFeasible(const Vector6d& v) const {
  const Pose pose = robot.PoseFromVector(v);
  if (!hexcal::IsFeasible(robot, pose)) return false;
  if (tracker) {
    for (double m : LineOfSightMargins(*tracker, robot, pose))
      if (!(m >= -kFeasibilityTolerance)) return false;
  }
  if (!measurement) return true;
  for (double m : MeasurementMargins(*measurement, pose)) {
    if (!(m >= -kFeasibilityTolerance)) return false;
  }
  return true;
}

namespace {

Status SettingsError(const std::string& path, const std::string& key, const std::string& problem) {
  return Status::BadInput("plan settings '" + path + "': " + key + ": " + problem);
}

StatusOr<double> FiniteNumber(const YAML::Node& node, const std::string& path, const std::string& key) {
  try {
    const double value = node.as<double>();
    if (std::isfinite(value)) return value;
  } catch (const YAML::Exception&) {
  }
  return SettingsError(path, key, "expected a finite number");
}

StatusOr<Eigen::Vector3d> Vector3(const YAML::Node& node, const std::string& path, const std::string& key) {
  if (!node.IsSequence() || node.size() != 3) return SettingsError(path, key, "expected a list of 3 numbers");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    StatusOr<double> x = FiniteNumber(node[k], path, key);
    if (!x.ok()) return x.status();
    v[k] = *x;
  }
  return v;
}

StatusOr<Pose> PoseNode(const YAML::Node& node, const std::string& path, const std::string& key, const Robot& robot) {
  if (!node.IsMap()) return SettingsError(path, key, "expected {position: [x, y, z], rotation_deg: [q1, q2, q3]}");
  for (const auto& item : node) {
    if (!item.first.IsScalar()) return SettingsError(path, key, "a key that is not a name");
    const std::string name = item.first.as<std::string>();
    if (name != "position" && name != "rotation_deg")
      return SettingsError(path, key + "." + YamlKeyText(item.first), "unknown key");
  }
  StatusOr<Eigen::Vector3d> position = Vector3(node["position"], path, key + ".position");
  if (!position.ok()) return position.status();
  StatusOr<Eigen::Vector3d> rotation = Vector3(node["rotation_deg"], path, key + ".rotation_deg");
  if (!rotation.ok()) return rotation.status();
  Vector6d v;
  v << *position, *rotation;
  return robot.PoseFromVector(v);
}

}  // namespace

namespace {

StatusOr<PlanSettings> ReadPlanSettings(const YAML::Node& root, const std::string& path, const Robot& robot) {
  if (!root.IsMap()) return Status::BadInput("plan settings '" + path + "': expected a mapping at the top level");
  static const std::set<std::string> kKeys = {"noise",  "planner",           "camera",
                                                 "target", "field_of_view_deg", "max_view_angle_deg"};
  for (const auto& item : root) {
    if (!item.first.IsScalar()) return SettingsError(path, "top level", "a key that is not a name");
    const std::string key = item.first.as<std::string>();
    if (!kKeys.count(key)) return SettingsError(path, YamlKeyText(item.first), "unknown key");
  }
  PlanSettings settings;
  if (root["noise"]) {
    StatusOr<NoiseModel> noise = ReadNoiseSection(root["noise"], "plan settings '" + path + "': noise");
    if (!noise.ok()) return noise.status();
    settings.noise = *noise;
  }
  if (root["planner"]) {
    StatusOr<std::vector<std::pair<std::string, std::string>>> entries =
        ScalarEntries(root["planner"], "plan settings '" + path + "': planner");
    if (!entries.ok()) return entries.status();
    settings.planner = *entries;
  }
  const bool any_measurement = root["camera"] || root["target"] || root["field_of_view_deg"];
  if (any_measurement) {
    if (!root["camera"] || !root["target"] || !root["field_of_view_deg"]) {
      return SettingsError(path, "camera/target/field_of_view_deg", "measurement constraints need all three");
    }
    MeasurementConstraints c;
    StatusOr<Pose> camera = PoseNode(root["camera"], path, "camera", robot);
    if (!camera.ok()) return camera.status();
    StatusOr<Pose> target = PoseNode(root["target"], path, "target", robot);
    if (!target.ok()) return target.status();
    c.base_from_camera = *camera;
    c.platform_from_target = *target;
    const YAML::Node fov = root["field_of_view_deg"];
    if (!fov.IsSequence() || fov.size() != 2) return SettingsError(path, "field_of_view_deg", "expected [h, v]");
    StatusOr<double> h = FiniteNumber(fov[0], path, "field_of_view_deg"), v = FiniteNumber(fov[1], path, "field_of_view_deg");
    if (!h.ok()) return h.status();
    if (!v.ok()) return v.status();
    if (*h <= 0 || *h >= 180 || *v <= 0 || *v >= 180) return SettingsError(path, "field_of_view_deg", "angles must be in (0, 180)");
    c.half_fov_x_deg = *h / 2;
    c.half_fov_y_deg = *v / 2;
    if (root["max_view_angle_deg"]) {
      StatusOr<double> m = FiniteNumber(root["max_view_angle_deg"], path, "max_view_angle_deg");
      if (!m.ok()) return m.status();
      if (*m <= 0 || *m > 90) return SettingsError(path, "max_view_angle_deg", "must be in (0, 90]");
      c.max_view_angle_deg = *m;
    }
    settings.measurement = c;
  }
  return settings;
}

}  // namespace

StatusOr<PlanSettings> ParsePlanSettings(const std::string& text, const std::string& path, const Robot& robot) {
  const std::string label = "plan settings '" + path + "'";
  StatusOr<YAML::Node> root = LoadYamlDocument(text, label);
  if (!root.ok()) return root.status();
  return WithYamlBackstop<PlanSettings>(label, [&] { return ReadPlanSettings(*root, path, robot); });
}

StatusOr<PlanSettings> LoadPlanSettings(const std::string& path, const Robot& robot) {
  StatusOr<std::string> text = ReadFileToString(path);
  if (!text.ok()) return text.status().Prefixed("plan settings: ");
  return ParsePlanSettings(*text, path, robot);
}

}  // namespace hexcal

#include "core/noise_model.h"

#include <cmath>
#include <limits>

#include "core/inverse_kinematics.h"

namespace hexcal {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d s;
  s << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return s;
}

Eigen::Matrix3d Axis(int k, double q) {
  return Eigen::AngleAxisd(q, Eigen::Vector3d::Unit(k)).matrix();
}

}  // namespace

bool NoiseModel::IsValid(std::string* error) const {
  for (double v : {position, angle_deg, leg}) {
    if (!std::isfinite(v) || v < 0) {
      *error = "noise levels must be finite and non-negative";
      return false;
    }
  }
  return true;
}

const OptionTable<NoiseModel>& NoiseModelOptions() {
  static const OptionTable<NoiseModel> table = [] {
    OptionTable<NoiseModel> t;
    const auto number = [&t](std::string key, std::string flag, std::string label, std::string unit,
                             std::string help, double NoiseModel::*field) {
      OptionSpec<NoiseModel> spec;
      spec.key = std::move(key);
      spec.flag = std::move(flag);
      spec.label = std::move(label);
      spec.unit = std::move(unit);
      spec.max = std::numeric_limits<double>::infinity();
      spec.help = std::move(help);
      spec.get_number = [field](const NoiseModel& n) { return n.*field; };
      spec.set_number = [field](NoiseModel& n, double v) { n.*field = v; };
      t.push_back(std::move(spec));
    };
    number("position", "position", "Noise: position", "robot unit",
           "half-width of the uniform noise on the measured x, y, z", &NoiseModel::position);
    number("angle_deg", "angle", "Noise: angle", "deg", "half-width of the uniform noise on the measured q1, q2, q3",
           &NoiseModel::angle_deg);
    number("leg", "leg", "Noise: leg reading", "robot unit", "half-width of the uniform noise on each leg reading",
           &NoiseModel::leg);
    return t;
  }();
  return table;
}

std::string NoiseModelText(const NoiseModel& noise, const std::string& separator) {
  std::string text;
  for (const OptionSpec<NoiseModel>& spec : NoiseModelOptions())
    text += (text.empty() ? "" : separator) + spec.key + ": " + OptionText(spec, noise);
  return text;
}

// Uniform on [-h, h] has variance h²/3.
double NoiseModel::PositionStdDev() const { return position / std::sqrt(3.0); }
double NoiseModel::AngleStdDevRad() const { return DegToRad(angle_deg) / std::sqrt(3.0); }
double NoiseModel::LegStdDev() const { return leg / std::sqrt(3.0); }

std::array<Eigen::Matrix3d, 3> RotationEulerPartials(const Eigen::Vector3d& q, EulerConvention convention) {
  // xyz: R = Rz(q3) Ry(q2) Rx(q1); zyx: R = Rx(q3) Ry(q2) Rz(q1). d/dq Ra(q) = [e_a]x Ra(q).
  const int first = convention == EulerConvention::kXYZ ? 0 : 2;
  const int last = convention == EulerConvention::kXYZ ? 2 : 0;
  const Eigen::Matrix3d r1 = Axis(first, q[0]), r2 = Axis(1, q[1]), r3 = Axis(last, q[2]);
  const Eigen::Vector3d e1 = Eigen::Vector3d::Unit(first), e2 = Eigen::Vector3d::UnitY(),
                        e3 = Eigen::Vector3d::Unit(last);
  return {r3 * r2 * Skew(e1) * r1, r3 * Skew(e2) * r2 * r1, Skew(e3) * r3 * r2 * r1};
}

MeasuredPose MeasuredPoseOf(const Robot& robot, const Vector6d& pose_vector) {
  const Eigen::Vector3d q(DegToRad(pose_vector[3]), DegToRad(pose_vector[4]), DegToRad(pose_vector[5]));
  return {robot.PoseFromVector(pose_vector), RotationEulerPartials(q, robot.euler)};
}

Eigen::Matrix<double, 7, 1> ResidualMeasurementGradient(const Leg& leg, const MeasuredPose& measured, double reading) {
  const Eigen::Vector3d v = LegVector(leg, measured.pose);
  Eigen::Matrix<double, 7, 1> g;
  g.head<3>() = 2 * v;  // ∂|v|²/∂P
  for (int k = 0; k < 3; ++k) g[3 + k] = 2 * v.dot(measured.rotation_partials[k] * leg.b_in_platform);
  g[6] = -2 * (reading + leg.offset);
  return g;
}

Eigen::Matrix<double, 7, 1> ResidualMeasurementGradient(const Robot& robot, int leg_index,
                                                        const Vector6d& pose_vector, double reading) {
  return ResidualMeasurementGradient(robot.legs[leg_index], MeasuredPoseOf(robot, pose_vector), reading);
}

double ResidualStdDev(const Leg& leg, const MeasuredPose& measured, double reading, const NoiseModel& noise) {
  const Eigen::Matrix<double, 7, 1> g = ResidualMeasurementGradient(leg, measured, reading);
  const double sp = noise.PositionStdDev(), sq = noise.AngleStdDevRad(), sl = noise.LegStdDev();
  const double variance = g.head<3>().squaredNorm() * sp * sp + g.segment<3>(3).squaredNorm() * sq * sq +
                          g[6] * g[6] * sl * sl;
  return std::sqrt(variance);
}

double ResidualStdDev(const Robot& robot, int leg, const Vector6d& pose_vector, double reading,
                      const NoiseModel& noise) {
  return ResidualStdDev(robot.legs[leg], MeasuredPoseOf(robot, pose_vector), reading, noise);
}

double ResidualStdDev(const Robot& robot, int leg, const Vector6d& pose_vector, double reading,
                      const NoiseModel& noise, const Matrix6d& pose_covariance) {
  return ResidualStdDev(robot.legs[leg], MeasuredPoseOf(robot, pose_vector), reading, noise, pose_covariance);
}

double ResidualStdDev(const Leg& leg, const MeasuredPose& measured, double reading, const NoiseModel& noise,
                      const Matrix6d& pose_covariance) {
  Eigen::Matrix<double, 7, 1> g = ResidualMeasurementGradient(leg, measured, reading);
  g.segment<3>(3) *= DegToRad(1.0);  // per degree, as the covariance
  const double sl = noise.LegStdDev();
  const double variance = g.head<6>().dot(pose_covariance * g.head<6>()) + g[6] * g[6] * sl * sl;
  return std::sqrt(variance);
}

}  // namespace hexcal

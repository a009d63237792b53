// The measurement-noise model shared by the planner (noise-aware criteria),
// the calibration (residual weighting) and the simulation (paper section 7).
//
// A measurement is a pose [x, y, z, q1, q2, q3] and six readings L. Each
// component carries independent zero-mean noise, uniform on [-h, h] as in the
// paper (variance h²/3). The implicit residual F_ij (eq. 4) then has variance
//   Var(F_ij) = g_ijᵀ Σ g_ij,   g_ij = ∂F_ij/∂(x, y, z, q1, q2, q3, L_ij)
// with Σ = diag(σ_p², σ_p², σ_p², σ_q², σ_q², σ_q², σ_L²).
//
//   NoiseModel noise;  // the paper's: 0.001 cm, 0.01°, 0.001 cm
//   double sd = ResidualStdDev(robot, i, pose, reading, noise);
#pragma once

#include <array>
#include <string>

#include "core/option_spec.h"
#include "core/robot.h"

namespace hexcal {

struct NoiseModel {
  double position = 0.001;  // half-width of the uniform noise on x, y, z (robot unit)
  double angle_deg = 0.01;  // half-width on q1, q2, q3 (degrees)
  double leg = 0.001;       // half-width on each reading L_i (robot unit)

  bool IsValid(std::string* error) const;
  double PositionStdDev() const;
  double AngleStdDevRad() const;
  double LegStdDev() const;
};

// The three half-widths described once (core/option_spec.h): the `noise:`
// sections of session.yaml and plan settings, the --noise-* flags, the GUI.
const OptionTable<NoiseModel>& NoiseModelOptions();
// {"position": …, "angle_deg": …, "leg": …} as text, in the table's order
// ("position: 0.001, angle_deg: 0.01, leg: 0.001" with `separator` ", ").
std::string NoiseModelText(const NoiseModel& noise, const std::string& separator = ", ");

// dR/dq_k for the Euler angles of `convention` (q in radians).
std::array<Eigen::Matrix3d, 3> RotationEulerPartials(const Eigen::Vector3d& q_rad, EulerConvention convention);

// A measured pose and dR/dq_k at it: what every leg's residual gradient
// needs, computed once per pose rather than once per leg.
struct MeasuredPose {
  Pose pose;
  std::array<Eigen::Matrix3d, 3> rotation_partials;
};
MeasuredPose MeasuredPoseOf(const Robot& robot, const Vector6d& pose_vector);

// g = ∂F/∂(x, y, z, q1, q2, q3 [per radian], L) for leg i.
Eigen::Matrix<double, 7, 1> ResidualMeasurementGradient(const Robot& robot, int leg, const Vector6d& pose_vector,
                                                        double reading);
Eigen::Matrix<double, 7, 1> ResidualMeasurementGradient(const Leg& leg, const MeasuredPose& measured, double reading);

// √(gᵀ Σ g): the standard deviation of F_ij under the noise model.
double ResidualStdDev(const Robot& robot, int leg, const Vector6d& pose_vector, double reading,
                      const NoiseModel& noise);
double ResidualStdDev(const Leg& leg, const MeasuredPose& measured, double reading, const NoiseModel& noise);
// The same with the pose's own covariance (robot unit², degrees², any
// correlations) in place of the model's pose terms; the reading's from `noise`.
double ResidualStdDev(const Robot& robot, int leg, const Vector6d& pose_vector, double reading,
                      const NoiseModel& noise, const Matrix6d& pose_covariance);
double ResidualStdDev(const Leg& leg, const MeasuredPose& measured, double reading, const NoiseModel& noise,
                      const Matrix6d& pose_covariance);

}  // namespace hexcal

#include "core/registration.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/forward_kinematics.h"

namespace hexcal {

RegistrationOptions RegistrationOptionsFromNoise(const NoiseModel& noise) {
  RegistrationOptions options;
  options.position_sigma = noise.PositionStdDev();
  options.angle_sigma_deg = RadToDeg(noise.AngleStdDevRad());
  return options;
}

bool RegistrationOptions::IsValid(std::string* error) const {
  if (!(position_sigma > 0) || !std::isfinite(position_sigma)) {
    *error = "registration position_sigma must be a positive number";
    return false;
  }
  if (!(angle_sigma_deg > 0) || !std::isfinite(angle_sigma_deg)) {
    *error = "registration angle_sigma_deg must be a positive number";
    return false;
  }
  if (max_iterations < 1) {
    *error = "registration max_iterations must be at least 1";
    return false;
  }
  return true;
}

namespace {

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

bool IsFinite(const Pose& pose) { return pose.position.allFinite() && pose.rotation.allFinite(); }

// Step 1 and 2 of the header: linear rotations, then linear translations.
Status LinearRegistration(const std::vector<Pose>& a, const std::vector<Pose>& b, Pose* x, Pose* y) {
  const int n = static_cast<int>(a.size());
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  Eigen::MatrixXd system(9 * n, 18);
  for (int j = 0; j < n; ++j) {
    Eigen::Matrix<double, 9, 9> left = Eigen::Matrix<double, 9, 9>::Zero();
    Eigen::Matrix<double, 9, 9> right;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        left.block<3, 3>(3 * r, 3 * c) = r == c ? a[j].rotation : Eigen::Matrix3d::Zero();
        right.block<3, 3>(3 * r, 3 * c) = b[j].rotation(c, r) * identity;  // R_Bᵀ ⊗ I
      }
    system.block<9, 9>(9 * j, 0) = left;
    system.block<9, 9>(9 * j, 9) = -right;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(system, Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  // The solution is the null space; it must be one-dimensional, so the second
  // smallest singular value must stand clear of zero relative to the largest.
  if (sv(16) < 1e-6 * sv(0))
    return Status::Failed("registration: the poses do not determine the frames (too few distinct orientations)");
  const Eigen::VectorXd v = svd.matrixV().col(17);
  Eigen::Matrix3d ry_raw = Eigen::Map<const Eigen::Matrix3d>(v.data());
  Eigen::Matrix3d rx_raw = Eigen::Map<const Eigen::Matrix3d>(v.data() + 9);
  const double scale = std::cbrt(ry_raw.determinant());
  if (!(std::abs(scale) > 0)) return Status::Failed("registration: degenerate rotation estimate");
  y->rotation = NearestRotation(ry_raw / scale);
  x->rotation = NearestRotation(rx_raw / scale);

  Eigen::MatrixXd lhs(3 * n, 6);
  Eigen::VectorXd rhs(3 * n);
  for (int j = 0; j < n; ++j) {
    lhs.block<3, 3>(3 * j, 0) = a[j].rotation;
    lhs.block<3, 3>(3 * j, 3) = -identity;
    rhs.segment<3>(3 * j) = x->rotation * b[j].position - a[j].position;
  }
  const Eigen::VectorXd t = lhs.colPivHouseholderQr().solve(rhs);
  y->position = t.head<3>();
  x->position = t.tail<3>();
  return Status::Ok();
}

// Residual of one pair: A·(exp(δy) R_Y0, t_Y) against (exp(δx) R_X0, t_X)·B.
struct ClosureCost {
  ClosureCost(const Pose& a, const Pose& b, const Pose& x0, const Pose& y0, double position_sigma, double angle_sigma)
      : a(a), b(b), x0(x0), y0(y0), position_weight(1 / position_sigma), angle_weight(1 / angle_sigma) {}

  template <typename T>
  bool operator()(const T* dx, const T* tx, const T* dy, const T* ty, T* residual) const {
    using M3 = Eigen::Matrix<T, 3, 3>;
    using V3 = Eigen::Matrix<T, 3, 1>;
    M3 ex, ey;
    ceres::AngleAxisToRotationMatrix(dx, ex.data());  // column-major, as Eigen
    ceres::AngleAxisToRotationMatrix(dy, ey.data());
    const M3 rx = ex * x0.rotation.cast<T>();
    const M3 ry = ey * y0.rotation.cast<T>();
    const V3 t_x(tx[0], tx[1], tx[2]), t_y(ty[0], ty[1], ty[2]);
    const M3 r_platform = a.rotation.cast<T>() * ry;  // rotation of A·Y
    const V3 p_platform = a.rotation.cast<T>() * t_y + a.position.cast<T>();
    const M3 r_camera = rx * b.rotation.cast<T>();  // rotation of X·B
    const V3 p_camera = rx * b.position.cast<T>() + t_x;
    const M3 difference = r_camera.transpose() * r_platform;
    T angle_axis[3];
    ceres::RotationMatrixToAngleAxis(difference.data(), angle_axis);
    for (int k = 0; k < 3; ++k) {
      residual[k] = (p_platform[k] - p_camera[k]) * T(position_weight);
      residual[3 + k] = angle_axis[k] * T(angle_weight);
    }
    return true;
  }

  Pose a, b, x0, y0;
  double position_weight, angle_weight;
};

Eigen::Matrix3d ExpRotation(const double* angle_axis) {
  Eigen::Matrix3d r;
  ceres::AngleAxisToRotationMatrix(angle_axis, r.data());
  return r;
}

StatusOr<int> Refine(const std::vector<Pose>& a, const std::vector<Pose>& b, const RegistrationOptions& options,
                     Pose* x, Pose* y) {
  double dx[3] = {0, 0, 0}, dy[3] = {0, 0, 0};
  double tx[3] = {x->position.x(), x->position.y(), x->position.z()};
  double ty[3] = {y->position.x(), y->position.y(), y->position.z()};
  ceres::Problem problem;
  const double angle_sigma = DegToRad(options.angle_sigma_deg);
  for (size_t j = 0; j < a.size(); ++j) {
    auto* cost = new ceres::AutoDiffCostFunction<ClosureCost, 6, 3, 3, 3, 3>(
        new ClosureCost(a[j], b[j], *x, *y, options.position_sigma, angle_sigma));
    problem.AddResidualBlock(cost, nullptr, dx, tx, dy, ty);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-14;
  solver.gradient_tolerance = 1e-14;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (summary.termination_type != ceres::CONVERGENCE)
    return Status::Failed("registration: the refinement did not converge (" + summary.BriefReport() + ")");
  x->rotation = ExpRotation(dx) * x->rotation;
  y->rotation = ExpRotation(dy) * y->rotation;
  x->position = Eigen::Vector3d(tx[0], tx[1], tx[2]);
  y->position = Eigen::Vector3d(ty[0], ty[1], ty[2]);
  return static_cast<int>(summary.iterations.size());
}

void ClosureStatistics(const std::vector<Pose>& a, const std::vector<Pose>& b, Registration* reg) {
  double position_sum = 0, angle_sum = 0;
  reg->position_max = reg->angle_max_deg = 0;
  for (size_t j = 0; j < a.size(); ++j) {
    const Pose platform_side = Compose(a[j], reg->platform_from_target);
    const Pose camera_side = Compose(reg->base_from_camera, b[j]);
    const double position = (platform_side.position - camera_side.position).norm();
    const double angle = RadToDeg(RotationDistance(platform_side.rotation, camera_side.rotation));
    position_sum += position * position;
    angle_sum += angle * angle;
    reg->position_max = std::max(reg->position_max, position);
    reg->angle_max_deg = std::max(reg->angle_max_deg, angle);
  }
  reg->position_rms = std::sqrt(position_sum / a.size());
  reg->angle_rms_deg = std::sqrt(angle_sum / a.size());
}

}  // namespace

StatusOr<Registration> EstimateRegistration(const std::vector<Pose>& base_from_platform,
                                            const std::vector<Pose>& camera_from_target,
                                            const RegistrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput(error);
  if (base_from_platform.size() != camera_from_target.size())
    return Status::BadInput("registration: " + std::to_string(base_from_platform.size()) + " robot poses but " +
                            std::to_string(camera_from_target.size()) + " camera poses");
  if (base_from_platform.size() < 3)
    return Status::BadInput("registration needs at least 3 poses, got " + std::to_string(base_from_platform.size()));
  for (size_t j = 0; j < base_from_platform.size(); ++j)
    if (!IsFinite(base_from_platform[j]) || !IsFinite(camera_from_target[j]))
      return Status::BadInput("registration: pose " + std::to_string(j + 1) + " is not finite");

  Registration reg;
  Status linear =
      LinearRegistration(base_from_platform, camera_from_target, &reg.base_from_camera, &reg.platform_from_target);
  if (!linear.ok()) return linear;
  if (options.refine) {
    StatusOr<int> iterations =
        Refine(base_from_platform, camera_from_target, options, &reg.base_from_camera, &reg.platform_from_target);
    if (!iterations.ok()) return iterations.status();
    reg.iterations = *iterations;
  }
  ClosureStatistics(base_from_platform, camera_from_target, &reg);
  return reg;
}

Pose BaseFromPlatform(const Registration& registration, const Pose& camera_from_target) {
  return BaseFromPlatform(registration.base_from_camera, camera_from_target, registration.platform_from_target);
}

Robot ExpressInFrames(const Robot& robot, const Pose& new_base_from_old_base,
                      const Pose& new_platform_from_old_platform) {
  Robot moved = robot;
  for (Leg& leg : moved.legs) {
    leg.a_in_base = new_base_from_old_base * leg.a_in_base;
    leg.b_in_platform = new_platform_from_old_platform * leg.b_in_platform;
  }
  return moved;
}

Matrix6d MapCameraPoseCovariance(const Robot& nominal, const Registration& registration,
                                 const Pose& camera_from_target, const Matrix6d& covariance) {
  const Vector6d b = VectorFromPose(camera_from_target, EulerConvention::kXYZ);
  const auto mapped = [&](const Vector6d& v) {
    return nominal.VectorFromPose(BaseFromPlatform(registration, PoseFromVector(v, EulerConvention::kXYZ)));
  };
  // Steps well above rounding and well inside the linear range: 1e-6 of the
  // pose's size for positions, 1e-6 degree for angles.
  const double position_step = 1e-6 * std::max(1.0, b.head<3>().norm());
  Matrix6d jacobian;
  for (int k = 0; k < 6; ++k) {
    const double h = k < 3 ? position_step : 1e-6;
    Vector6d plus = b, minus = b;
    plus[k] += h;
    minus[k] -= h;
    jacobian.col(k) = (mapped(plus) - mapped(minus)) / (2 * h);
  }
  return jacobian * covariance * jacobian.transpose();
}

namespace {

// Local FK of the nominal robot from each image's readings.
StatusOr<std::vector<Pose>> NominalPoses(const Robot& nominal, const CameraCalibrationInput& input) {
  std::vector<Pose> poses;
  for (size_t j = 0; j < input.legs.size(); ++j) {
    StatusOr<LocalFkResult> fk = ForwardKinematicsLocal(nominal, input.legs[j], input.fk_start[j]);
    if (!fk.ok()) return Status::BadInput("pose " + std::to_string(j + 1) + ": " + fk.status().message());
    poses.push_back(fk->pose);
  }
  return poses;
}

// Registration on the images not in `left_out` (ascending).
StatusOr<Registration> RegisterWithout(const std::vector<Pose>& nominal_poses, const CameraCalibrationInput& input,
                                       const std::vector<int>& left_out, const RegistrationOptions& options) {
  std::vector<Pose> base_from_platform, camera_from_target;
  for (size_t j = 0, next = 0; j < nominal_poses.size(); ++j) {
    if (next < left_out.size() && left_out[next] == static_cast<int>(j)) {
      ++next;
      continue;
    }
    base_from_platform.push_back(nominal_poses[j]);
    camera_from_target.push_back(input.camera_from_target[j]);
  }
  return EstimateRegistration(base_from_platform, camera_from_target, options);
}

// The camera poses in the registered base frame, with the readings and covariances.
StatusOr<std::vector<Measurement>> MapToBase(const Robot& nominal, const Registration& reg,
                                             const CameraCalibrationInput& input) {
  std::vector<Measurement> measurements;
  for (size_t j = 0; j < input.camera_from_target.size(); ++j) {
    Measurement m;
    m.pose = nominal.VectorFromPose(BaseFromPlatform(reg, input.camera_from_target[j]));
    m.legs = input.legs[j];
    if (!input.camera_pose_covariance.empty()) {
      const Matrix6d& covariance = input.camera_pose_covariance[j];
      if (!covariance.allFinite())
        return Status::BadInput("pose " + std::to_string(j + 1) + ": the camera pose covariance is not finite");
      m.pose_covariance = MapCameraPoseCovariance(nominal, reg, input.camera_from_target[j], covariance);
    }
    measurements.push_back(m);
  }
  return measurements;
}

// Registration, mapping and calibration on every image but `left_out`'s registration.
Status RegisterAndCalibrate(const Robot& nominal, const CameraCalibrationInput& input,
                            const std::vector<Pose>& nominal_poses, const std::vector<int>& left_out,
                            const RegistrationOptions& registration_options,
                            const CalibrationOptions& calibration_options, const JobHooks& hooks,
                            CameraCalibrationResult* result) {
  StatusOr<Registration> reg = RegisterWithout(nominal_poses, input, left_out, registration_options);
  if (!reg.ok()) return reg.status();
  result->registration = *reg;
  StatusOr<std::vector<Measurement>> measurements = MapToBase(nominal, *reg, input);
  if (!measurements.ok()) return measurements.status();
  result->measurements = std::move(*measurements);
  StatusOr<CalibrationResult> calibration = Calibrate(nominal, result->measurements, calibration_options, hooks);
  if (!calibration.ok()) return calibration.status();
  result->calibration = std::move(*calibration);
  result->registration_left_out = left_out;
  return Status::Ok();
}

}  // namespace

StatusOr<CameraCalibrationResult> CalibrateFromCameraPoses(const Robot& nominal, const CameraCalibrationInput& input,
                                                           const RegistrationOptions& registration_options,
                                                           const CalibrationOptions& calibration_options,
                                                           const JobHooks& hooks) {
  const size_t n = input.camera_from_target.size();
  if (input.legs.size() != n || input.fk_start.size() != n ||
      (!input.camera_pose_covariance.empty() && input.camera_pose_covariance.size() != n))
    return Status::BadInput(
        "calibration from camera poses: camera poses, readings, FK starts and covariances differ in number");
  StatusOr<std::vector<Pose>> nominal_poses = NominalPoses(nominal, input);
  if (!nominal_poses.ok()) return nominal_poses.status();
  CameraCalibrationResult result;
  if (Status s = RegisterAndCalibrate(nominal, input, *nominal_poses, {}, registration_options, calibration_options,
                                      hooks, &result);
      !s.ok())
    return s;
  // A wrong reading also moved its image's FK pose, and with it the frames:
  // register again without those images, then calibrate in that gauge.
  const std::vector<int> left_out = ImagesWithExcludedOutliers(result.calibration);
  if (!left_out.empty()) {
    if (Status s = RegisterAndCalibrate(nominal, input, *nominal_poses, left_out, registration_options,
                                        calibration_options, hooks, &result);
        !s.ok())
      return s;
  }
  if (Status s = ComputeCalibratedClosure(&result); !s.ok()) return s;
  return result;
}

std::vector<int> ImagesWithExcludedOutliers(const CalibrationResult& calibration) {
  std::vector<int> images;
  for (const LegCalibration& leg : calibration.legs)
    for (const RowOutlier& o : leg.outliers)
      if (o.excluded) images.push_back(o.measurement);
  std::sort(images.begin(), images.end());
  images.erase(std::unique(images.begin(), images.end()), images.end());
  return images;
}

// A reading known to be wrong sends FK anywhere: the images holding one count
// in no RMS, but each keeps its row, which names it.
Status ComputeCalibratedClosure(CameraCalibrationResult* result) {
  std::vector<int> skip = ImagesWithExcludedOutliers(result->calibration);
  skip.insert(skip.end(), result->registration_left_out.begin(), result->registration_left_out.end());
  std::sort(skip.begin(), skip.end());
  skip.erase(std::unique(skip.begin(), skip.end()), skip.end());
  result->closure_left_out = skip;
  StatusOr<ValidationReport> all = Validate(result->calibration.robot, result->measurements);
  if (!all.ok()) return all.status();
  result->closure_rows = all->rows;
  double position_sum = 0, angle_sum = 0;
  int count = 0;
  for (size_t j = 0; j < all->rows.size(); ++j) {
    const ValidationRow& row = all->rows[j];
    if (!row.ok || std::binary_search(skip.begin(), skip.end(), static_cast<int>(j))) continue;
    position_sum += row.position_error * row.position_error;
    angle_sum += row.orientation_error_deg * row.orientation_error_deg;
    ++count;
  }
  if (count == 0) return Status::Failed("closure with the calibrated robot: forward kinematics converged on no image");
  result->calibrated_position_rms = std::sqrt(position_sum / count);
  result->calibrated_angle_rms_deg = std::sqrt(angle_sum / count);
  return Status::Ok();
}

}  // namespace hexcal

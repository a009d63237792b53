#include "core/point_calibration_cost.h"

#include <Eigen/QR>
#include <Eigen/SVD>

namespace hexcal {
namespace {

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

Eigen::MatrixXd ReflectorGaugeConstraints(const Eigen::VectorXd& start) {
  const int count = static_cast<int>(start.size() / 3);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int k = 0; k < count; ++k) centroid += start.segment<3>(3 * k) / count;
  Eigen::MatrixXd c(6, 3 * count);
  for (int k = 0; k < count; ++k) {
    c.block<3, 3>(0, 3 * k).setIdentity();
    c.block<3, 3>(3, 3 * k) = Cross(start.segment<3>(3 * k) - centroid);
  }
  return c;
}

ReflectorGaugeManifold::ReflectorGaugeManifold(const Eigen::VectorXd& start) {
  const int ambient = static_cast<int>(start.size());
  if (ambient < 9 || ambient % 3 != 0) {
    basis_ = Eigen::MatrixXd::Identity(ambient, ambient);
    return;
  }
  const Eigen::MatrixXd c = ReflectorGaugeConstraints(start);
  // The constraints are independent unless the reflectors lie on one line;
  // measured relative to their largest singular value, scale-free.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeFullV);
  const Eigen::VectorXd values = svd.singularValues();
  valid_ = values[5] > 1e-9 * values[0];
  basis_ = svd.matrixV().rightCols(ambient - 6);
}

bool ReflectorGaugeManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  Eigen::Map<const Eigen::VectorXd> from(x, AmbientSize());
  Eigen::Map<const Eigen::VectorXd> step(delta, TangentSize());
  Eigen::Map<Eigen::VectorXd>(x_plus_delta, AmbientSize()) = from + basis_ * step;
  return true;
}

bool ReflectorGaugeManifold::PlusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobian, AmbientSize(),
                                                                                     TangentSize()) = basis_;
  return true;
}

bool ReflectorGaugeManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  Eigen::Map<const Eigen::VectorXd> to(y, AmbientSize()), from(x, AmbientSize());
  Eigen::Map<Eigen::VectorXd>(y_minus_x, TangentSize()) = basis_.transpose() * (to - from);
  return true;
}

bool ReflectorGaugeManifold::MinusJacobian(const double*, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      jacobian, TangentSize(), AmbientSize()) = basis_.transpose();
  return true;
}

}  // namespace hexcal

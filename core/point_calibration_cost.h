// Inside the calibration from points (point_calibration.h): the residual of
// one measured point and the reflectors' gauge, for Ceres. Internal: includes
// Ceres, which only hexcal_core links.
//
// Point residual, for reflector k seen at pose j (tracker frame, robot unit):
//   e_jk = (X⁻¹ · (R(ω_j) r_k + t_j) − m_jk) / σ_jk,
// over the pose block [ω_j, t_j] (6, angle-axis as the leg residual's) and the
// block of every reflector [r_1 … r_K] (3K, platform frame), of which it
// touches r_k's three columns only; X = base_from_tracker is held fixed.
//
// Reflector gauge: with the reflectors estimated, the platform frame is the
// frame of the b_i and the r_k together, and moving both by one rigid motion
// H (b_i → H b_i, r_k → H r_k, A_j → A_j H⁻¹) changes no residual. The
// reflectors' block therefore moves only in the (3K − 6)-dimensional subspace
//   Σ_k δr_k = 0,   Σ_k (r⁰_k − c⁰) × δr_k = 0   (c⁰ their centroid at the start),
// which keeps their centroid and their mean orientation where the start put
// them (the registration's platform frame): the constraint matrix restricted to
// the rigid motions is [K·I, ·; 0, Σ(|d|²I − d dᵀ)], invertible unless the
// reflectors lie on one line. Plus(r, δ) = r + N δ with N an orthonormal basis
// of that subspace.
#pragma once

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "core/pose.h"

namespace hexcal {

// X⁻¹ (R(ω) r + t) − m, over σ; blocks: pose (6), one reflector (3).
struct PointFunctor {
  Eigen::Matrix3d tracker_from_base_rotation;
  Eigen::Vector3d tracker_from_base_translation;
  Eigen::Vector3d measured;  // m, tracker frame
  double sigma = 1;          // σ of each coordinate

  template <typename T>
  bool operator()(const T* pose, const T* reflector, T* residual) const {
    T in_base[3];
    ceres::AngleAxisRotatePoint(pose, reflector, in_base);
    for (int k = 0; k < 3; ++k) in_base[k] += pose[3 + k];
    for (int r = 0; r < 3; ++r) {
      T in_tracker = T(tracker_from_base_translation[r]);
      for (int k = 0; k < 3; ++k) in_tracker += T(tracker_from_base_rotation(r, k)) * in_base[k];
      residual[r] = (in_tracker - T(measured[r])) / T(sigma);
    }
    return true;
  }
};

// PointFunctor over the whole reflector block: blocks pose (6), reflectors (3K).
class PointResidualCost final : public ceres::CostFunction {
 public:
  PointResidualCost(const Pose& base_from_tracker, const Eigen::Vector3d& measured, double sigma, int reflector,
                    int reflectors)
      : reflector_(reflector), reflectors_(reflectors) {
    const Pose tracker_from_base = Inverse(base_from_tracker);
    functor_.tracker_from_base_rotation = tracker_from_base.rotation;
    functor_.tracker_from_base_translation = tracker_from_base.position;
    functor_.measured = measured;
    functor_.sigma = sigma;
    set_num_residuals(3);
    mutable_parameter_block_sizes()->assign({6, 3 * reflectors});
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* reflector = parameters[1] + 3 * reflector_;
    if (jacobians == nullptr) return functor_(parameters[0], reflector, residuals);
    using Jet = ceres::Jet<double, 9>;
    Jet pose[6], point[3], out[3];
    for (int k = 0; k < 6; ++k) pose[k] = Jet(parameters[0][k], k);
    for (int k = 0; k < 3; ++k) point[k] = Jet(reflector[k], 6 + k);
    if (!functor_(pose, point, out)) return false;
    for (int r = 0; r < 3; ++r) {
      residuals[r] = out[r].a;
      if (jacobians[0] != nullptr)
        for (int k = 0; k < 6; ++k) jacobians[0][6 * r + k] = out[r].v[k];
      if (jacobians[1] != nullptr) {
        double* row = jacobians[1] + 3 * reflectors_ * r;
        std::fill(row, row + 3 * reflectors_, 0.0);
        for (int k = 0; k < 3; ++k) row[3 * reflector_ + k] = out[r].v[6 + k];
      }
    }
    return true;
  }

  int reflector() const { return reflector_; }
  const PointFunctor& functor() const { return functor_; }

 private:
  PointFunctor functor_;
  int reflector_, reflectors_;
};

// The reflectors' block moved within the gauge subspace above.
class ReflectorGaugeManifold final : public ceres::Manifold {
 public:
  // `start`: the reflectors [r_1 … r_K] where the gauge holds them. Check
  // `valid()`: false for fewer than 3 reflectors or reflectors on one line.
  explicit ReflectorGaugeManifold(const Eigen::VectorXd& start);

  bool valid() const { return valid_; }
  // N: 3K × (3K − 6), orthonormal columns.
  const Eigen::MatrixXd& basis() const { return basis_; }

  int AmbientSize() const override { return static_cast<int>(basis_.rows()); }
  int TangentSize() const override { return static_cast<int>(basis_.cols()); }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;

 private:
  Eigen::MatrixXd basis_;
  bool valid_ = false;
};

// The 6 × 3K gauge constraint matrix C (C δr = 0 above) of reflectors `start`.
Eigen::MatrixXd ReflectorGaugeConstraints(const Eigen::VectorXd& start);

}  // namespace hexcal

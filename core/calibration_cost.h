// The Ceres cost of one implicit residual (paper eq. 4/5), for core/calibration.cc
// and its tests. Internal: includes Ceres, which only hexcal_core links.
//
//   r = F / w,  F = |P + R b - a|² - (L + l)²,
//   dr/d(a, b, l) = [-2v, 2Rᵀv, -2(L + l)] / w,  v = P + R b - a
// over the leg's parameter block [a_x a_y a_z b_x b_y b_z l].
#pragma once

#include <ceres/ceres.h>

#include "core/identification.h"

namespace hexcal {

// A leg whose a, b and l are `parameters` (stroke unset: not used by F).
inline Leg LegFromParameters(const double* parameters) {
  Leg leg;
  leg.a_in_base = Eigen::Vector3d(parameters[0], parameters[1], parameters[2]);
  leg.b_in_platform = Eigen::Vector3d(parameters[3], parameters[4], parameters[5]);
  leg.offset = parameters[6];
  return leg;
}

class ImplicitLegCost final : public ceres::SizedCostFunction<1, kParamsPerLeg> {
 public:
  // `weight` is w > 0: 1 for the paper's cost, the residual's standard deviation when weighted.
  ImplicitLegCost(const Pose& pose, double reading, double weight)
      : pose_(pose), reading_(reading), inverse_weight_(1.0 / weight) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Leg leg = LegFromParameters(parameters[0]);
    residuals[0] = ImplicitResidual(leg, pose_, reading_) * inverse_weight_;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<JacobianRow> row(jacobians[0]);
      row = ImplicitJacobianRow(leg, pose_, reading_) * inverse_weight_;
    }
    return std::isfinite(residuals[0]);
  }

 private:
  Pose pose_;
  double reading_;
  double inverse_weight_;
};

}  // namespace hexcal

#include "core/observability.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace hexcal {

SingularValues SingularValuesOf(const InformationBlocks& info) {
  SingularValues sigma;
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::SelfAdjointEigenSolver<InfoBlock> eigen(info.blocks[i], Eigen::EigenvaluesOnly);
    // Round-off leaves the zero eigenvalues of a rank-deficient block (fewer than 7 poses, or
    // repeated ones) at about ±eps·λ_max, either sign; anything below the rank tolerance
    // 7·eps·λ_max is zero, or a degenerate pose set gets a small non-zero O1 and O3.
    const auto lambda = eigen.eigenvalues().array();
    const double rank_tolerance = kParamsPerLeg * std::numeric_limits<double>::epsilon() * lambda.maxCoeff();
    sigma.segment<kParamsPerLeg>(kParamsPerLeg * i) = (lambda > rank_tolerance).select(lambda.sqrt(), 0.0);
  }
  std::sort(sigma.data(), sigma.data() + kNumParams, std::greater<double>());
  return sigma;
}

ObservabilityIndices ComputeIndices(const InformationBlocks& info) {
  const SingularValues sigma = SingularValuesOf(info);
  ObservabilityIndices o;
  o.num_poses = info.num_poses;
  o.sigma_max = sigma[0];
  o.sigma_min = sigma[kNumParams - 1];
  if (o.sigma_max <= 0 || info.num_poses <= 0) return o;
  o.o2 = o.sigma_min / o.sigma_max;
  o.o3 = o.sigma_min;
  o.o4 = o.sigma_min * o.sigma_min / o.sigma_max;
  if (o.sigma_min > 0) {
    // Geometric mean through logs: the plain product of 42 values over- or underflows.
    const double mean_log = sigma.array().log().sum() / kNumParams;
    o.o1 = std::exp(mean_log) / std::sqrt(static_cast<double>(info.num_poses));
  }
  return o;
}

ObservabilityIndices ComputeIndices(const Robot& robot, const std::vector<Pose>& poses) {
  return ComputeIndices(ComputeInformation(robot, poses));
}

std::string IndexMeaning(int k) {
  switch (k) {
    case 1:
      return "(sigma_1 ... sigma_42)^(1/42) / sqrt(poses): the volume of the parameters' uncertainty (D-optimality)";
    case 2:
      return "sigma_min / sigma_max: the conditioning of the identification Jacobian";
    case 3:
      return "sigma_min: the worst-identified direction of the parameters";
    case 4:
      return "sigma_min^2 / sigma_max: how much the noise is amplified";
  }
  return "";
}

std::string IndexUnit(int k, const std::string& length_unit) {
  // J_P's rows are [-2v, 2R^T v, -2(L + l)] (eq. 5): lengths, so its singular
  // values are lengths; O2 is their ratio.
  return k == 2 ? "" : length_unit;
}

}  // namespace hexcal

// Observability indices of a pose set (paper section 2, Nahvi & Hollerbach 1996),
// from the singular values σ_1 >= ... >= σ_L of the identification Jacobian J_P:
//   O1 = (σ_1 ··· σ_L)^(1/L) / √m      (m poses, L = 42; the D-criterion in disguise)
//   O2 = σ_L / σ_1                      (inverse condition number; unit-free)
//   O3 = σ_L
//   O4 = σ_L² / σ_1
// J_P is block-diagonal (eq. 6), so its 42 singular values are the union of
// the six 7x7 blocks' singular values, σ = √eig(M_i). Lengths in the robot unit.
#pragma once

#include <string>

#include "core/identification.h"

namespace hexcal {

using SingularValues = Eigen::Matrix<double, kNumParams, 1>;

struct ObservabilityIndices {
  double o1 = 0, o2 = 0, o3 = 0, o4 = 0;
  double sigma_min = 0, sigma_max = 0;
  int num_poses = 0;
};

// All 42 singular values, sorted descending.
SingularValues SingularValuesOf(const InformationBlocks& info);
ObservabilityIndices ComputeIndices(const InformationBlocks& info);
ObservabilityIndices ComputeIndices(const Robot& robot, const std::vector<Pose>& poses);

// For printed output: what O<k> (k = 1..4) is and its unit. Each is larger
// for a better pose set.
//   IndexMeaning(3) = "sigma_min: the worst-identified direction of the parameters"
//   IndexUnit(3, "cm") = "cm"; IndexUnit(2, "cm") = "" (a ratio)
std::string IndexMeaning(int k);
std::string IndexUnit(int k, const std::string& length_unit);

}  // namespace hexcal

// The S criterion: the predicted standard deviations of the 42 parameters
// themselves (docs/planner.md, "The S criterion").
//
// With noise-weighted rows M_i is the inverse covariance of leg i's
// least-squares estimate, so σ_ij = √(M_i⁻¹)_jj is the standard deviation of
// parameter j of leg i, and the mean |error| a calibration leaves is about
// √(2/π) times the mean σ. S = 42 / Σ σ_ij is the reciprocal of the mean σ:
// maximising S minimises the expected parameter error, which is what
// calibrating is for. Like A it is a rank-one update (Sherman–Morrison):
//   (M + r rᵀ)⁻¹_jj = (M⁻¹)_jj - u_j² / (1 + rᵀu),   u = M⁻¹ r
// and by the same lemma (M - r rᵀ)⁻¹ = M⁻¹ + u uᵀ / (1 - rᵀu) for a removal.
//
// Σ_j √(e_jᵀ M⁻¹ e_j) is convex in M (each term is h(M)^(-1/2) with
// h(M) = 1 / e_jᵀM⁻¹e_j concave), so its approximate design has an
// equivalence theorem and a certified bound (sigma_design.h).
#pragma once

#include <array>

#include "core/identification.h"

namespace hexcal {

// Σ_j √(M⁻¹)_jj of one leg, from M⁻¹.
double SigmaSum(const InfoBlock& inverse);

// Σ over the legs of Σ_j σ_j after adding candidate j, for every candidate in
// [begin, begin + n) (the legs' M_i⁻¹ given).
void SigmaSumsAfterAdding(const std::array<InfoBlock, kNumLegs>& inverses,
                          const std::array<Eigen::Matrix<double, kParamsPerLeg, Eigen::Dynamic>, kNumLegs>& candidates,
                          int begin, int n, double* sums);

// The Σσ after adding one pose with rows r_i, and its gradient w.r.t. each r_i:
//   ∂Σ_j σ_j / ∂r = -M⁻¹(u ⊘ σ) / (1 + q) + (Σ_j u_j² / σ_j) u / (1 + q)²,  q = rᵀu.
double SigmaSumAfterAddingWithGradient(const std::array<InfoBlock, kNumLegs>& inverses,
                                       const std::array<JacobianRow, kNumLegs>& rows,
                                       std::array<JacobianRow, kNumLegs>* gradient);

}  // namespace hexcal

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

// A lower bound of the Σσ after adding each candidate in [begin, begin + n),
// given its quadratic forms q_i = r_iᵀM_i⁻¹r_i (forms[i][j], QuadraticFormCache).
// With u = M⁻¹r and c_k² = u_k²/((M⁻¹)_kk q) <= 1 (Cauchy–Schwarz), σ_k falls
// by σ_k g(c_k²), g(x) = 1 - √(1 - x q/(1 + q)), convex with g(0) = 0, so
// g(x) <= x g(1) and a leg's Σσ falls by at most
//   φ(q) Σ_k u_k²/σ_k = φ(q) rᵀWr,  W = M⁻¹ diag(σ)⁻¹ M⁻¹,  φ(q) = 1/(√(1+q)(√(1+q)+1))
// (and by at most q φ(q) Σ_k σ_k, every c_k = 1): 28 multiply-adds and one
// square root per leg through W's Cholesky factor, against 49 and seven.
// The candidates' rows come one column per parameter (n x 7), so that the
// sums run along contiguous candidates; the per-leg factors (U with W = UᵀU,
// and Σ_k σ_k) once per design.
using ParameterColumns = Eigen::Matrix<double, Eigen::Dynamic, kParamsPerLeg>;
// The same rows rounded to float: half the memory a pass over 10⁵ candidates
// reads (QuadraticFormCache's single precision); the sums stay in double.
using ParameterColumns32 = Eigen::Matrix<float, Eigen::Dynamic, kParamsPerLeg>;
struct SigmaBoundFactors {
  std::array<InfoBlock, kNumLegs> upper;
  std::array<double, kNumLegs> sigma_sum;
};
SigmaBoundFactors SigmaBoundFactorsOf(const std::array<InfoBlock, kNumLegs>& inverses);
void SigmaSumLowerBounds(const SigmaBoundFactors& factors, const std::array<ParameterColumns, kNumLegs>& candidates,
                         const std::array<const double*, kNumLegs>& forms, int begin, int n, double* least_sums);
void SigmaSumLowerBounds(const SigmaBoundFactors& factors, const std::array<ParameterColumns32, kNumLegs>& candidates,
                         const std::array<const double*, kNumLegs>& forms, int begin, int n, double* least_sums);

// The Σσ after adding one pose with rows r_i, and its gradient w.r.t. each r_i:
//   ∂Σ_j σ_j / ∂r = -M⁻¹(u ⊘ σ) / (1 + q) + (Σ_j u_j² / σ_j) u / (1 + q)²,  q = rᵀu.
double SigmaSumAfterAddingWithGradient(const std::array<InfoBlock, kNumLegs>& inverses,
                                       const std::array<JacobianRow, kNumLegs>& rows,
                                       std::array<JacobianRow, kNumLegs>* gradient);

}  // namespace hexcal

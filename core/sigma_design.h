// The certificate of the S criterion (sigma_criterion.h, docs/planner.md):
// the optimal approximate design for the summed parameter standard deviations.
//
// Weights w_j >= 0, Σ w_j = 1 on the candidates minimise
//   Φ(w) = Σ_i Σ_k √(M_i(w)⁻¹)_kk,   M_i(w) = Σ_j w_j r_ij r_ijᵀ,
// the Σσ of one pose's worth of information (N poses: Φ / √N). Φ is convex,
// and its directional derivative towards candidate x is (Φ - d(x, w)) / 2 with
//   d(x, w) = Σ_i |S_i⁻½ M_i⁻¹ r_i(x)|²,   S_i = diag(σ_i1, ..., σ_i7),
// so w is optimal iff d(x, w) <= Φ(w) for every x (equality on the support).
// ψ = Φ⁻² is concave and homogeneous of degree 1 (a generalised mean of the
// concave 1 / (M⁻¹)_kk), hence ψ(M*) <= ψ(M(w)) · max_x d / Φ(w) for any w:
//   Φ* >= Φ(w) · √(Φ(w) / max_x d)                               (the bound)
// and an N-pose plan's S-efficiency Φ* / (√N Σσ_plan) is at least the bound
// over √N Σσ_plan. Weights come from the multiplicative algorithm
// w_j <- w_j (d_j / Φ)^½ (Yu 2010's exponent for A-type criteria), finished
// with vertex exchanges whose step is found by golden-section search.
#pragma once

#include <vector>

#include "core/optimal_design.h"

namespace hexcal {

struct SigmaDesign {
  std::vector<double> weights;  // per candidate, summing to 1
  double sigma_sum = 0;         // Φ(w)
  double max_d = 0;             // max_x d(x, w); Φ(w) at the optimum
  double gap = 0;               // max_d / Φ(w) - 1
  int iterations = 0;
  int support = 0;              // candidates with weight > 1e-8
  bool converged = false;
  // Φ* >= Φ(w) √(Φ(w) / max_d): no design of one pose's weight does better.
  double SigmaSumBound() const;
};

// hooks.cancel stops it (Status::Cancelled).
StatusOr<SigmaDesign> ComputeSigmaOptimalDesign(const CandidateRows& candidates,
                                                const OptimalDesignOptions& options = {},
                                                const JobHooks& hooks = {});

// Φ along a vertex exchange: weight δ moved from candidate `from` to candidate
// `to`, M_i(δ) = M_i + δ (r_to r_toᵀ - r_from r_fromᵀ). By Woodbury, with
// A = M_i⁻¹, p = A r_to, q = A r_from, a = r_toᵀp, b = r_fromᵀq, c = r_toᵀq,
//   M_i(δ)⁻¹_kk = A_kk - δ [(1 - δb) p_k² + 2δc p_k q_k - (1 + δa) q_k²] / g(δ),
//   g(δ) = (1 + δa)(1 - δb) + δ²c² = det M_i(δ) / det M_i,
// and g is concave (c² <= ab) with g(0) = 1, so M_i(δ) is positive definite
// exactly while g(δ) > 0. Each δ costs O(7) per leg, not a factorisation.
class SigmaSumAlongExchange {
 public:
  SigmaSumAlongExchange(const std::array<InfoBlock, kNumLegs>& blocks, const CandidateRows& candidates, int to,
                        int from);
  // Φ(M(δ)); infinity where M(δ) is not positive definite (or M itself is not).
  double operator()(double delta) const;

 private:
  using Vector7d = Eigen::Matrix<double, kParamsPerLeg, 1>;
  struct Leg {
    Vector7d variance, p, q;  // diag A, A r_to, A r_from
    double a = 0, b = 0, c = 0;
  };
  std::array<Leg, kNumLegs> legs_;
  bool positive_definite_ = true;
};

// Certified lower bound on the S-efficiency of a plan of `num_poses` poses with
// information `plan_blocks`: Φ* / (√N Σσ_plan), in (0, 1].
double SEfficiencyLowerBound(const std::array<InfoBlock, kNumLegs>& plan_blocks, int num_poses,
                             const SigmaDesign& design);

}  // namespace hexcal

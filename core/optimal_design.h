// The optimality certificate of a plan on a finite candidate set.
//
// The optimal approximate design puts weights w_j >= 0, Σ w_j = 1, on the
// candidates to maximise log det M(w), M(w) = Σ_j w_j M_j, where M_j is
// candidate j's block-diagonal information (one rank-one term per leg). By the
// Kiefer–Wolfowitz equivalence theorem w is optimal iff the variance function
//   d(x, w) = Σ_i r_i(x)ᵀ M_i(w)⁻¹ r_i(x)
// is at most p = 42 for every candidate (with equality on the support), and
// for any w the optimum is bounded: det(M*)^(1/p) <= det(M(w))^(1/p) · max_x d(x, w) / p.
//
// Weights are found by the multiplicative algorithm (Silvey, Titterington &
// Torsney 1978), w_j <- w_j d_j / p, finished by vertex-exchange steps
// (Böhning 1986: move weight from the worst support point to the best
// candidate with the optimal step) until the gap max d / p - 1 is below the
// tolerance. A plan of N poses then has the certified D-efficiency
//   (det(M_plan / N) / det M*)^(1/42) >= (det(M_plan / N) / det M(w))^(1/42) · p / max d.
#pragma once

#include <vector>

#include "core/design_criteria.h"
#include "core/job_hooks.h"
#include "core/optimal_design_options.h"
#include "core/planning_model.h"
#include "core/status.h"

namespace hexcal {

struct OptimalDesign {
  std::vector<double> weights;  // per candidate, summing to 1
  double log_det = 0;           // log det M(w)
  double max_variance = 0;      // max_x d(x, w); 42 at the optimum
  double gap = 0;               // max_variance / 42 - 1
  int iterations = 0;
  int support = 0;              // candidates with weight > 1e-8
  bool converged = false;
  // log det M* <= log det M(w) + 42 log(max_variance / 42): the certified bound.
  double LogDetBound() const;
};

// hooks.cancel stops it (Status::Cancelled); it reports no progress, as its
// length is set by the gap and the time limit rather than a count.
StatusOr<OptimalDesign> ComputeOptimalDesign(const CandidateRows& candidates, const OptimalDesignOptions& options = {},
                                             const JobHooks& hooks = {});

// M_i(w) = Σ_j w_j r_ij r_ijᵀ for every leg.
std::array<InfoBlock, kNumLegs> DesignInformation(const CandidateRows& candidates, const Eigen::ArrayXd& w);

// d(x_j, w) for every candidate, given the per-leg inverses of M(w).
void VarianceFunction(const std::array<InfoBlock, kNumLegs>& inverses, const CandidateRows& candidates,
                      Eigen::ArrayXd* variance);

// Certified lower bound on the D-efficiency of a plan whose information blocks are
// `plan_blocks` (N poses), against the design: (det(M/N) / det M*)^(1/42).
double DEfficiencyLowerBound(const std::array<InfoBlock, kNumLegs>& plan_blocks, int num_poses,
                             const OptimalDesign& design);


}  // namespace hexcal

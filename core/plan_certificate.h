// The certificates of a plan on a finite candidate set: its D-efficiency
// (optimal_design.h) and its S-efficiency (sigma_design.h), each a certified
// lower bound against the best approximate design on the same candidates.
#pragma once

#include <vector>

#include "core/optimal_design.h"
#include "core/sigma_design.h"

namespace hexcal {

struct PlanCertificate {
  OptimalDesign design;
  double d_efficiency = 0;  // certified lower bound, in (0, 1]
  SigmaDesign sigma_design;
  double s_efficiency = 0;  // certified lower bound, in (0, 1]
  // The smallest mean parameter standard deviation any N-pose plan on these
  // candidates can have: Φ* / (42 √N) >= this (model rows' unit).
  double BestMeanSigma(int num_poses) const;
};

// Both design bounds over `candidates` and the plan's efficiencies against them:
// D on the model's rows (weighted when the model has a noise model), S on rows
// weighted by the model's noise or else the paper's levels, as the S criterion.
// Each design gets the options' time limit; the two run side by side.
// `known_rows`, when given, are model.RowsOf of a prefix of `candidates`
// (the planner's), not computed again.
StatusOr<PlanCertificate> CertifyPlan(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                                      const std::vector<Vector6d>& plan, const OptimalDesignOptions& options = {},
                                      const CandidateRows* known_rows = nullptr);

}  // namespace hexcal

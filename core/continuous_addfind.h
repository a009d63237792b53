// AddFind over the continuous workspace (paper fig. 2b): from each start, a
// local constrained maximisation of the criterion of the current set plus one
// pose, by SLSQP (NLopt) over [x, y, z, q1, q2, q3] inside the pose box and
// under every robot and measurement constraint. The criterion's gradient is
// analytic in the Jacobian rows (determinant lemma for D/O1, Sherman–Morrison
// for A, eigenvalue perturbation dλ = 2 (uᵀr) uᵀdr for O2-O4 and E), chained
// through d(rows)/d(pose); constraint gradients are central differences.
#pragma once

#include <vector>

#include "core/planning_model.h"

namespace hexcal {

struct ContinuousResult {
  Vector6d pose;
  double value = 0;  // criterion of the set plus this pose
};

// One result per start whose optimum is feasible, in the order of the starts;
// the starts run on `threads` cores (0: every core).
std::vector<ContinuousResult> ContinuousAddFind(const PlanningModel& model, const DesignState& state,
                                                Criterion criterion, const std::vector<Vector6d>& starts,
                                                int max_evaluations = 100, int threads = 0);

// Criterion of `state` plus the pose, and its gradient w.r.t. the pose vector.
double CriterionAndGradient(const PlanningModel& model, const DesignState& state, Criterion criterion,
                            const Vector6d& pose, Vector6d* gradient);

}  // namespace hexcal

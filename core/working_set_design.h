// Approximate designs over many candidates by a working set (column
// generation; docs/planner.md, "Optimality certificates"): the optimal design
// of 10⁴–10⁶ candidates has a support of a few dozen, so it is solved on a few
// hundred candidates, every candidate is priced by the directional function at
// that solution, the most violating ones join the working set, and so on until
// the gap over *all* candidates is below the tolerance. The certificate is the
// pricing's: its bound holds whatever the working set was.
//
//   Design: weights, gap, iterations, support, converged (OptimalDesign, SigmaDesign).
//   solve(rows, options, hooks)      -> StatusOr<Design> on those rows only
//   price(all, working, design, &d)  -> the design on `working` evaluated over `all`:
//                                       d per candidate, the design's gap over all;
//                                       returns the threshold above which d violates
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <vector>

#include "core/design_criteria.h"
#include "core/job_hooks.h"
#include "core/optimal_design_options.h"
#include "core/status.h"

namespace hexcal {

// Rows of the candidates `indices`, in that order.
CandidateRows GatherRows(const CandidateRows& all, const std::vector<int>& indices);
// The `count` candidates with the largest d that `member` does not hold, largest first.
std::vector<int> LargestOutside(const Eigen::ArrayXd& d, const std::vector<char>& member, int count, double above);

constexpr int kWorkingSetStart = 512;   // candidates in the first working set
constexpr int kWorkingSetGrowth = 256;  // most violating candidates added per pass

template <typename Design, typename Solve, typename Price>
StatusOr<Design> SolveOnWorkingSet(const CandidateRows& all, const OptimalDesignOptions& options,
                                   const JobHooks& hooks, Solve solve, Price price) {
  if (all.size() <= 4 * kWorkingSetStart) return solve(all, options, hooks);
  const auto start = std::chrono::steady_clock::now();
  Eigen::ArrayXd d;
  Design design;  // uniform weights on every candidate: the first pricing
  design.weights.assign(all.size(), 1.0 / all.size());
  price(all, all, &design, &d);
  std::vector<char> member(all.size(), 0);
  std::vector<int> working_set = LargestOutside(d, member, kWorkingSetStart, -1);
  int iterations = 0;
  while (true) {
    for (int j : working_set) member[j] = 1;
    const CandidateRows working = GatherRows(all, working_set);
    OptimalDesignOptions inner = options;
    inner.gap_tolerance = 0.5 * options.gap_tolerance;
    inner.max_seconds = options.max_seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (inner.max_seconds <= 0) break;
    StatusOr<Design> solved = solve(working, inner, hooks);
    if (!solved.ok()) return solved.status();
    iterations += solved->iterations;
    design = *solved;
    const double threshold = price(all, working, &design, &d);
    // Spread the working weights over all candidates, for the caller.
    std::vector<double> weights(all.size(), 0.0);
    for (size_t k = 0; k < working_set.size(); ++k) weights[working_set[k]] = solved->weights[k];
    design.weights = std::move(weights);
    design.iterations = iterations;
    design.support = static_cast<int>(std::count_if(design.weights.begin(), design.weights.end(), [](double w) { return w > 1e-8; }));
    design.converged = design.gap < options.gap_tolerance;
    if (design.converged) return design;
    const std::vector<int> added = LargestOutside(d, member, kWorkingSetGrowth, threshold);
    if (added.empty()) return design;  // nothing violates beyond the working set: the inner gap is the limit
    working_set.insert(working_set.end(), added.begin(), added.end());
  }
  return design;
}

}  // namespace hexcal

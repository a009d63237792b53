// The quadratic forms of every candidate pose against the plan's information,
// kept up to date through IOOPS's exchanges (split from design_criteria.h,
// whose DesignState they follow).
//
//   QuadraticFormCache cache;
//   cache.Reset(state, candidates);
//   cache.Exchanged(state, added, with_added, removed, candidates);
//   cache.Growth(&growth);  // Π_i (1 + q_ij): ranks candidates as D and O1 do
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/design_criteria.h"
#include "core/sigma_criterion.h"

namespace hexcal {

// The quadratic forms q_ij = r_ijᵀ M_i⁻¹ r_ij of every candidate j, kept up to
// date through the plan's exchanges by Sherman–Morrison: adding a pose with
// rows a changes q by -(rᵀM⁻¹a)² / (1 + aᵀM⁻¹a), removing b by
// +(rᵀM⁻¹b)² / (1 - bᵀM⁻¹b): 14 multiply-adds per leg and candidate instead of
// a 35-operation triangular solve. Π_i (1 + q_ij) ranks candidates exactly as
// D and O1 do (determinant lemma). Refreshed from scratch now and then against drift.
class QuadraticFormCache {
 public:
  // With single_precision the rows are kept as float, half the memory each
  // exchange reads: q is then that of the rows rounded to float, good for the
  // S bounds (whose slack covers the rounding), not for an exact Growth. When
  // a sample shows the rounding moving the bounds by more than a tenth of
  // that slack (an ill-conditioned plan), the rows are kept double instead.
  void Reset(const DesignState& state, const CandidateRows& candidates, int threads = 0,
             bool single_precision = false);
  bool single_precision() const { return single_; }
  // Call with the state *before* the change.
  void Added(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows);
  void Removed(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows);
  // One exchange in one pass over the candidates (they are read once, not twice):
  // `before` is the state before adding `added`, `with_added` the state after it.
  // With `after` (the state once `removed` is gone) and `sigma_bounds`, the
  // same pass also gives SigmaUpperBounds(after): the candidates are read from
  // memory once per exchange, not twice.
  void Exchanged(const DesignState& before, const PoseRows& added, const DesignState& with_added,
                 const PoseRows& removed, const CandidateRows& candidates, int threads = 0,
                 const DesignState* after = nullptr, std::vector<double>* sigma_bounds = nullptr);
  // Π_i (1 + q_ij) for every candidate.
  void Growth(std::vector<double>* growth) const;
  // An upper bound of the S of `state` plus each candidate (SigmaSumLowerBounds,
  // sigma_criterion.h), on `threads` cores.
  void SigmaUpperBounds(const DesignState& state, std::vector<double>* bounds, int threads = 0) const;
  int updates_since_reset() const { return updates_; }

 private:
  void Update(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows, double sign);
  // S upper bounds of candidates [begin, end) from q and the factors of SigmaBoundFactorsOf.
  void SigmaUpperBoundsOf(const SigmaBoundFactors& factors, int begin, int end, double* bounds) const;
  std::array<Eigen::ArrayXd, kNumLegs> q_;
  // The candidates' rows one column per parameter (n x 7), copied on the first
  // Reset: the updates and bounds then run along contiguous candidates.
  std::array<ParameterColumns, kNumLegs> columns_;      // double precision, or
  std::array<ParameterColumns32, kNumLegs> columns32_;  // single precision
  bool single_ = false;
  const CandidateRows* source_ = nullptr;
  int updates_ = 0;
};

}  // namespace hexcal

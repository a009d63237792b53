// Which of AddFind's scored candidates IOOPS adds (section 6.2): the best on
// the primary criterion, or, with a secondary, the best on it among the
// `keep` fraction best on the primary; split from ioops.cc, which calls them
// once per iteration.
//
//   std::vector<double> primary = ..., secondary = ...;   // one score per candidate
//   int pick = SelectBest(primary, &secondary, 0.8);        // -1: none is finite
#pragma once

#include <vector>

#include "core/design_criteria.h"

namespace hexcal {

// Candidates scored per ParallelFor item: a multiple of ScoreAdditions' own
// 256-column chunks, large enough that the items cost far more than handing them out.
constexpr int kScoreBlock = 1024;

// The `keep` fraction of the finite entries best on `primary`, in no particular order.
std::vector<int> KeptOnPrimary(const std::vector<double>& primary, double keep);

// Index of the best entry (-1 when none is finite).
int SelectBest(const std::vector<double>& primary, const std::vector<double>* secondary, double keep);

// The best of `subset` (null: every finite bound) on `criterion`, exact values
// computed only while an upper bound can still beat the best found.
int BestByBounds(const std::vector<int>* subset, const std::vector<double>& bounds, const DesignState& state,
                 Criterion criterion, const CandidateRows& scored);

// SelectBest with an eigenvalue secondary (O2-O4, E), screened by its upper bounds.
int SelectBestScreened(const DesignState& state, Criterion secondary, const CandidateRows& scored,
                       const std::vector<double>& primary, double keep, int threads);

}  // namespace hexcal

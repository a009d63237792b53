// The section 6.2 choice among AddFind's scored candidates (split from
// ioops.cc): keep the best fraction on the primary criterion, pick on the
// secondary, or screen by upper bounds before computing exact values.
#include "core/ioops_selection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace hexcal {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

// The entries with a finite primary value.
// Calls visit(j) for each j of `subset`, or, when there is no subset, for
// every j whose bound is finite (above -inf: not excluded).
template <typename Visit>
void ForEachEntry(const std::vector<int>* subset, const std::vector<double>& bounds, Visit visit) {
  if (subset) {
    for (int j : *subset) visit(j);
    return;
  }
  for (int j = 0; j < static_cast<int>(bounds.size()); ++j) {
    if (bounds[j] > kMinusInfinity) visit(j);
  }
}

std::vector<int> FiniteEntries(const std::vector<double>& primary) {
  std::vector<int> order;
  ForEachEntry(nullptr, primary, [&](int j) { order.push_back(j); });
  return order;
}

}  // namespace

// The `keep` fraction best on `primary` (section 6.2), in no particular order.
std::vector<int> KeptOnPrimary(const std::vector<double>& primary, double keep) {
  std::vector<int> order = FiniteEntries(primary);
  if (order.empty()) return order;
  const size_t kept = std::min(order.size(), std::max<size_t>(1, static_cast<size_t>(std::ceil(keep * order.size()))));
  std::nth_element(order.begin(), order.begin() + (kept - 1), order.end(),
                   [&](int a, int b) { return primary[a] > primary[b]; });
  order.resize(kept);
  return order;
}

// Index of the best entry: among the `keep` fraction best on `primary`, the best on `secondary`
// (section 6.2), or simply the best on `primary`.
int SelectBest(const std::vector<double>& primary, const std::vector<double>* secondary, double keep) {
  if (!secondary) {
    const std::vector<int> order = FiniteEntries(primary);
    if (order.empty()) return -1;
    return *std::min_element(order.begin(), order.end(), [&](int a, int b) { return primary[a] > primary[b]; });
  }
  const std::vector<int> kept = KeptOnPrimary(primary, keep);
  if (kept.empty()) return -1;
  return *std::max_element(kept.begin(), kept.end(), [&](int a, int b) { return (*secondary)[a] < (*secondary)[b]; });
}

// The best of `subset` (null: of every candidate with a finite bound) on
// `criterion` given an upper bound of each candidate's value: the candidates in
// decreasing order of bound, their exact values (ScoreAdditions) computed in
// batches only while a bound can still beat the best value found. Ties go to
// the lower candidate index, as in SelectBest.
int BestByBounds(const std::vector<int>* subset, const std::vector<double>& bounds, const DesignState& state,
                 Criterion criterion, const CandidateRows& scored) {
  const auto by_bound = [&](int a, int b) { return bounds[a] > bounds[b] || (bounds[a] == bounds[b] && a < b); };
  constexpr int kBatch = 16;
  CandidateRows batch;
  std::array<double, kBatch> values;
  int best = -1;
  double best_value = kMinusInfinity;
  auto evaluate = [&](const int* batch_indices, int size) {
    batch.Resize(size);
    for (int k = 0; k < size; ++k) batch.Set(k, scored.Rows(batch_indices[k]));
    state.ScoreAdditions(criterion, batch, 0, size, values.data());
    for (int k = 0; k < size; ++k) {
      if (values[k] > best_value || (values[k] == best_value && batch_indices[k] < best)) {
        best_value = values[k], best = batch_indices[k];
      }
    }
  };
  // The kBatch best bounds first, kept sorted in one pass (most candidates
  // fail the first comparison); then only the candidates whose bound can still
  // win, in decreasing order (a handful: sorting them all would cost more).
  std::vector<int> top;
  ForEachEntry(subset, bounds, [&](int j) {
    if (top.size() == kBatch && !by_bound(j, top.back())) return;
    if (top.size() == kBatch) top.pop_back();
    top.insert(std::upper_bound(top.begin(), top.end(), j, by_bound), j);
  });
  if (top.empty()) return -1;
  evaluate(top.data(), static_cast<int>(top.size()));
  std::vector<int> open;
  ForEachEntry(subset, bounds, [&](int j) {
    if (bounds[j] >= best_value && by_bound(top.back(), j)) open.push_back(j);
  });
  std::sort(open.begin(), open.end(), by_bound);
  for (size_t k = 0; k < open.size() && bounds[open[k]] >= best_value; k += kBatch) {
    evaluate(open.data() + k, static_cast<int>(std::min<size_t>(kBatch, open.size() - k)));
  }
  return best;
}

// SelectBest with an eigenvalue secondary (O2-O4, E), the same choice at a
// fraction of the cost: BestByBounds on the kept candidates with an upper
// bound of the secondary (DesignState::ScoreUpperBounds) instead of twelve
// secular equations per candidate.
int SelectBestScreened(const DesignState& state, Criterion secondary, const CandidateRows& scored,
                       const std::vector<double>& primary, double keep, int threads) {
  std::vector<double> bounds(scored.size());
  ParallelForBlocks(scored.size(), kScoreBlock, threads, [&](int begin, int end) {
    state.ScoreUpperBounds(secondary, scored, begin, end, bounds.data() + begin);
  });
  const std::vector<int> kept = KeptOnPrimary(primary, keep);
  return BestByBounds(&kept, bounds, state, secondary, scored);
}

}  // namespace hexcal

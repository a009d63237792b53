#include "core/ioops.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <random>

#include "core/continuous_addfind.h"
#include "core/parallel.h"

namespace hexcal {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
// Candidates scored per ParallelFor item: a multiple of ScoreAdditions' own
// 256-column chunks, large enough that the items cost far more than handing them out.
constexpr int kScoreBlock = 1024;

struct PlanEntry {
  Vector6d pose;
  PoseRows rows;
  int64_t id;  // candidate index, or a fresh negative id for initial and continuous poses
};

std::vector<Vector6d> PosesOf(const std::vector<PlanEntry>& plan) {
  std::vector<Vector6d> poses;
  for (const PlanEntry& entry : plan) poses.push_back(entry.pose);
  return poses;
}

ObservabilityIndices PaperIndices(const Robot& robot, const std::vector<PlanEntry>& plan) {
  std::vector<Pose> poses;
  for (const PlanEntry& entry : plan) poses.push_back(robot.PoseFromVector(entry.pose));
  return ComputeIndices(robot, poses);
}

// Index of the best entry: among the `keep` fraction best on `primary`, the best on `secondary`
// (section 6.2), or simply the best on `primary`.
int SelectBest(const std::vector<double>& primary, const std::vector<double>* secondary, double keep) {
  std::vector<int> order;
  for (int j = 0; j < static_cast<int>(primary.size()); ++j) {
    if (primary[j] > kMinusInfinity) order.push_back(j);
  }
  if (order.empty()) return -1;
  auto by_primary = [&](int a, int b) { return primary[a] > primary[b]; };
  if (!secondary) return *std::min_element(order.begin(), order.end(), by_primary);
  const size_t kept = std::min(order.size(), std::max<size_t>(1, static_cast<size_t>(std::ceil(keep * order.size()))));
  std::nth_element(order.begin(), order.begin() + (kept - 1), order.end(), by_primary);
  return *std::max_element(order.begin(), order.begin() + kept,
                           [&](int a, int b) { return (*secondary)[a] < (*secondary)[b]; });
}

}  // namespace

bool PlannerOptions::IsValid(std::string* error) const {
  if (num_poses < kParamsPerLeg) {
    *error = "the plan needs at least 7 poses to identify a leg's 7 parameters, got " + std::to_string(num_poses);
    return false;
  }
  if (!(keep > 0 && keep <= 1)) {
    *error = "keep must be in (0, 1]";
    return false;
  }
  if (tabu < 0 || iterations < 0 || addfind_starts < 0 || removal_choices < 1 || threads < 0) {
    *error = "tabu, iterations, addfind starts and threads must be >= 0, removal choices >= 1";
    return false;
  }
  if (tabu >= num_poses) {
    *error = "the Tabu list (" + std::to_string(tabu) + ") must be shorter than the plan (" +
             std::to_string(num_poses) + ")";
    return false;
  }
  if (!(criterion_switch_probability >= 0 && criterion_switch_probability <= 1)) {
    *error = "criterion switch probability must be in [0, 1]";
    return false;
  }
  if (criterion_switch_probability > 0 && !secondary) {
    *error = "criterion switching needs a secondary criterion";
    return false;
  }
  return true;
}

int PlannerOptions::IterationBudget() const {
  if (iterations > 0) return iterations;
  return tabu > 0 ? 200 : 10 * num_poses;
}

void ScoreInParallel(const DesignState& state, Criterion criterion, const CandidateRows& candidates,
                     std::vector<double>* scores, int threads) {
  scores->resize(candidates.size());
  ParallelForBlocks(candidates.size(), kScoreBlock, threads, [&](int begin, int end) {
    state.ScoreAdditions(criterion, candidates, begin, end, scores->data() + begin);
  });
}

StatusOr<PlanResult> PlanPoses(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                               const std::vector<Vector6d>& initial, const PlannerOptions& options,
                               const JobHooks& hooks, const PlanIterationObserver& on_iteration) {
  const auto start_time = std::chrono::steady_clock::now();
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  if (static_cast<int>(initial.size()) != options.num_poses) {
    return Status::Error("the initial set has " + std::to_string(initial.size()) + " poses, the plan " +
                         std::to_string(options.num_poses));
  }
  if (candidates.empty()) return Status::Error("the candidate set is empty");
  std::mt19937_64 rng(options.seed);

  const int count = static_cast<int>(candidates.size());
  CandidateRows rows;
  rows.Resize(count);
  for (int j = 0; j < count; ++j) rows.Set(j, model.Rows(candidates[j]));

  std::vector<PlanEntry> plan;
  int64_t next_new_id = -1;
  for (const Vector6d& pose : initial) plan.push_back({pose, model.Rows(pose), next_new_id--});
  std::vector<PoseRows> initial_rows;
  for (const PlanEntry& entry : plan) initial_rows.push_back(entry.rows);
  DesignState state = DesignState::FromRows(initial_rows);
  if (!state.full_rank()) {
    return Status::Error("the initial poses do not identify all 42 parameters (a leg's information matrix is "
                         "singular): start from more varied poses");
  }
  std::vector<char> in_plan(count, 0);

  const Criterion selection = options.secondary.value_or(options.criterion);
  std::vector<Vector6d> best = PosesOf(plan);
  double best_value = state.Value(selection);
  PlanResult result;
  auto record = [&](int iteration, bool exchanged) {
    PlanIteration step{iteration,
                       PaperIndices(model.robot, plan),
                       state.Value(options.criterion),
                       options.secondary ? state.Value(*options.secondary) : 0.0,
                       exchanged,
                       best_value};
    result.history.push_back(step);
    if (on_iteration) on_iteration(step);
  };
  record(0, false);
  result.initial = result.history.back().indices;
  result.initial_primary = result.history.back().primary;
  std::deque<int64_t> tabu;

  const int budget = options.IterationBudget();
  const int starts = options.addfind_starts > 0 ? options.addfind_starts : (options.continuous ? 40 : count);
  std::vector<double> primary_scores, secondary_scores;
  // D and O1 over every candidate: keep the quadratic forms through the exchanges
  // instead of recomputing them (QuadraticFormCache).
  const bool cached = !options.continuous && starts >= count &&
                      (options.criterion == Criterion::kO1 || options.criterion == Criterion::kD);
  QuadraticFormCache cache;
  if (cached) cache.Reset(state, rows);
  for (int iteration = 1; iteration <= budget; ++iteration) {
    if (hooks.Cancelled()) return Status::Cancelled("planning cancelled at iteration " + std::to_string(iteration));
    Criterion add_criterion = options.criterion;
    std::uniform_real_distribution<double> unit(0, 1);
    const bool switched = options.criterion_switch_probability > 0 && unit(rng) < options.criterion_switch_probability;
    if (switched) add_criterion = *options.secondary;
    const bool use_secondary = !switched && options.secondary.has_value();
    const Criterion secondary = options.secondary.value_or(options.criterion);

    // AddFind (figs 2a, 2b).
    PlanEntry added;
    if (!options.continuous) {
      CandidateRows subset_rows;
      std::vector<int> subset;
      const CandidateRows* scored = &rows;
      if (starts < count) {
        subset.resize(count);
        std::iota(subset.begin(), subset.end(), 0);
        for (int k = 0; k < starts; ++k) std::swap(subset[k], subset[k + rng() % (count - k)]);
        subset.resize(starts);
        subset_rows.Resize(starts);
        for (int k = 0; k < starts; ++k) subset_rows.Set(k, rows.Rows(subset[k]));
        scored = &subset_rows;
      }
      if (cached && !switched) {
        if (cache.updates_since_reset() >= 50) cache.Reset(state, rows);
        cache.Growth(&primary_scores);  // ranks candidates as the criterion does
      } else {
        ScoreInParallel(state, add_criterion, *scored, &primary_scores, options.threads);
      }
      if (use_secondary) ScoreInParallel(state, secondary, *scored, &secondary_scores, options.threads);
      for (int k = 0; k < scored->size(); ++k) {
        if (in_plan[subset.empty() ? k : subset[k]]) primary_scores[k] = kMinusInfinity;
      }
      const int pick = SelectBest(primary_scores, use_secondary ? &secondary_scores : nullptr, options.keep);
      if (pick < 0) return Status::Error("every candidate is already in the plan: the candidate set is too small");
      const int index = subset.empty() ? pick : subset[pick];
      added = {candidates[index], rows.Rows(index), index};
      in_plan[index] = 1;
    } else {
      std::vector<Vector6d> start_poses;
      for (int k = 0; k < starts; ++k) start_poses.push_back(candidates[rng() % count]);
      const std::vector<ContinuousResult> found = ContinuousAddFind(model, state, add_criterion, start_poses);
      if (found.empty()) return Status::Error("continuous AddFind found no feasible pose from " + std::to_string(starts) + " starts");
      primary_scores.clear();
      secondary_scores.clear();
      for (const ContinuousResult& r : found) {
        primary_scores.push_back(r.value);
        if (use_secondary) secondary_scores.push_back(state.ValueAfterAdding(secondary, model.Rows(r.pose)));
      }
      const int pick = SelectBest(primary_scores, use_secondary ? &secondary_scores : nullptr, options.keep);
      added = {found[pick].pose, model.Rows(found[pick].pose), next_new_id--};
    }
    plan.push_back(added);
    std::optional<DesignState> before_add;
    if (cached) before_add = state;
    state.Add(added.rows);
    if (options.tabu > 0) {
      tabu.push_back(added.id);
      if (static_cast<int>(tabu.size()) > options.tabu) tabu.pop_front();
    }

    // RemoveFind (figs 3, 4).
    std::vector<std::pair<double, int>> removals;
    for (int k = 0; k < static_cast<int>(plan.size()); ++k) {
      if (std::find(tabu.begin(), tabu.end(), plan[k].id) != tabu.end()) continue;
      removals.push_back({state.ValueAfterRemoving(options.criterion, plan[k].rows), k});
    }
    std::sort(removals.begin(), removals.end(), std::greater<>());
    const int choices = std::min<int>(options.removal_choices, removals.size());
    const int removed_index = removals[choices > 1 ? rng() % choices : 0].second;
    const PlanEntry removed = plan[removed_index];
    plan.erase(plan.begin() + removed_index);
    if (cached && removed.id != added.id) cache.Exchanged(*before_add, added.rows, state, removed.rows, rows);
    state.Remove(removed.rows);
    if (removed.id >= 0) in_plan[removed.id] = 0;

    const bool exchanged = removed.id != added.id;
    result.iterations = iteration;
    const double value = state.Value(selection);
    if (value > best_value) {
      best_value = value;
      best = PosesOf(plan);
      result.best_iteration = iteration;
    }
    record(iteration, exchanged);
    hooks.Progress(iteration, budget);
    if (!exchanged && options.tabu == 0) {
      result.converged = true;
      break;
    }
  }

  result.poses = best;
  std::vector<PoseRows> best_rows;
  std::vector<Pose> best_poses;
  for (const Vector6d& pose : best) {
    best_rows.push_back(model.Rows(pose));
    best_poses.push_back(model.robot.PoseFromVector(pose));
  }
  result.final = ComputeIndices(model.robot, best_poses);
  result.final_primary = DesignState::FromRows(best_rows).Value(options.criterion);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace hexcal

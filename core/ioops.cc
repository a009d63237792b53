// IOOPS as the paper draws it (section 4): PlanPoses is the loop of fig. 1,
// Exchange one iteration of it, AddFindFinite fig. 2a, AddFindContinuous
// fig. 2b, RememberAdded the Tabu list of section 4.3, RemoveFind figs 3 and 4.
#include "core/ioops.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <random>

#include "core/continuous_addfind.h"
#include "core/ioops_selection.h"
#include "core/quadratic_form_cache.h"
#include "core/parallel.h"

namespace hexcal {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

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

Status CheckPlanInput(const std::vector<Vector6d>& candidates, const std::vector<Vector6d>& initial,
                      const PlannerOptions& options) {
  if (Status s = options.Check(); !s.ok()) return s;
  if (static_cast<int>(initial.size()) != options.num_poses) {
    return Status::BadInput("the initial set has " + std::to_string(initial.size()) + " poses, the plan " +
                            std::to_string(options.num_poses));
  }
  if (candidates.empty()) return Status::BadInput("the candidate set is empty");
  return Status::Ok();
}

// What the exchange loop (fig. 1) carries from one iteration to the next: the
// plan Υ^N with its information, the candidate set, the Tabu list T and the
// random stream of the section 4.2 randomisation.
struct Search {
  Search(const PlanningModel& model, const std::vector<Vector6d>& candidates, const CandidateRows* given_rows,
         const std::vector<Vector6d>& initial, const PlannerOptions& options);

  const PlanningModel& model;
  const std::vector<Vector6d>& candidates;  // Ω_d (fig. 2a), or the start list of fig. 2b
  const PlannerOptions& options;
  std::mt19937_64 rng;
  CandidateRows own_rows;       // computed here when the caller gave none
  const CandidateRows& rows;    // of every candidate (finite search only)
  int64_t next_new_id = -1;     // ids of the poses that are not candidates: -1, -2, ...
  std::vector<PlanEntry> plan;  // Υ^N; Υ^{N+1} between AddFind and RemoveFind
  DesignState state;            // the information of `plan`
  std::vector<char> in_plan;    // per candidate
  std::deque<int64_t> tabu;     // T: ids of the last n added poses (section 4.3)
  int starts = 0;               // U
  // D and O1 over every candidate: keep the quadratic forms through the
  // exchanges instead of recomputing them (QuadraticFormCache); S alone over
  // every candidate: the same forms bound it (sigma_screened).
  bool cached = false;
  bool sigma_screened = false;
  std::vector<double> sigma_bounds;  // S bounds of `state`, from the last exchange's pass
  bool bounds_current = false;
  QuadraticFormCache cache;
  std::vector<double> primary_scores, secondary_scores;  // AddFind's, reused
};

std::vector<PlanEntry> InitialPlan(const PlanningModel& model, const std::vector<Vector6d>& initial,
                                   int64_t* next_new_id) {
  std::vector<PlanEntry> plan;
  for (const Vector6d& pose : initial) plan.push_back({pose, model.Rows(pose), (*next_new_id)--});
  return plan;
}

std::vector<PoseRows> RowsOf(const std::vector<PlanEntry>& plan) {
  std::vector<PoseRows> rows;
  for (const PlanEntry& entry : plan) rows.push_back(entry.rows);
  return rows;
}

Search::Search(const PlanningModel& model, const std::vector<Vector6d>& candidates, const CandidateRows* given_rows,
               const std::vector<Vector6d>& initial, const PlannerOptions& options)
    : model(model),
      candidates(candidates),
      options(options),
      rng(options.seed),
      // Continuous: the candidates are starts only, no rows.
      own_rows(given_rows || options.continuous ? CandidateRows{} : model.RowsOf(candidates, options.threads)),
      rows(given_rows ? *given_rows : own_rows),
      plan(InitialPlan(model, initial, &next_new_id)),
      state(DesignState::FromRows(RowsOf(plan))),
      in_plan(candidates.size(), 0) {
  const int count = static_cast<int>(candidates.size());
  starts = options.addfind_starts > 0 ? options.addfind_starts : (options.continuous ? 40 : count);
  const bool every_candidate = !options.continuous && starts >= count;
  sigma_screened = every_candidate && options.screen && options.criterion == Criterion::kS && !options.secondary;
  cached = sigma_screened ||
           (every_candidate && (options.criterion == Criterion::kO1 || options.criterion == Criterion::kD));
  // PlanPoses refuses a singular start. S alone keeps the rows as float: they
  // only bound it, and the exact S of double rows decides.
  if (cached && state.full_rank()) cache.Reset(state, rows, options.threads, sigma_screened);
  // An initial pose that is one of the candidates (a subset of measured poses,
  // core/subset_study.h) is that candidate: AddFind must not add it a second time.
  for (PlanEntry& entry : plan) {
    for (int j = 0; j < count; ++j) {
      if (!in_plan[j] && candidates[j] == entry.pose) {
        entry.id = j;
        in_plan[j] = 1;
        break;
      }
    }
  }
}

// The criteria of one AddFind: C_a is the primary criterion, or the secondary
// with the section 4.2 switch probability; unswitched, with a secondary
// criterion, AddFind keeps the best `keep` on C_a and picks on the secondary
// (section 6.2).
struct AddCriteria {
  Criterion add;
  bool switched = false;
  std::optional<Criterion> secondary;  // empty when switched or when there is none
};

AddCriteria DrawAddCriteria(const PlannerOptions& options, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  AddCriteria criteria{options.criterion, false, std::nullopt};
  criteria.switched = options.criterion_switch_probability > 0 && unit(rng) < options.criterion_switch_probability;
  if (criteria.switched) {
    criteria.add = *options.secondary;
  } else {
    criteria.secondary = options.secondary;
  }
  return criteria;
}

// The U candidates fig. 2a chooses in Ω_d: U drawn without replacement (a
// partial Fisher–Yates shuffle), or, empty, every candidate.
std::vector<int> DrawSubset(int count, int starts, std::mt19937_64& rng) {
  std::vector<int> subset;
  if (starts >= count) return subset;
  subset.resize(count);
  std::iota(subset.begin(), subset.end(), 0);
  for (int k = 0; k < starts; ++k) std::swap(subset[k], subset[k + rng() % (count - k)]);
  subset.resize(starts);
  return subset;
}

// AddFind on a finite Ω_d (fig. 2a): ζ+ is the ζ_i among the U candidates that
// maximises C_a(Υ^N + {ζ_i}); a candidate already in the plan is not a choice.
StatusOr<PlanEntry> AddFindFinite(Search& s, const AddCriteria& criteria) {
  const std::vector<int> subset = DrawSubset(s.rows.size(), s.starts, s.rng);
  auto candidate_of = [&](int k) { return subset.empty() ? k : subset[k]; };
  CandidateRows subset_rows;
  subset_rows.Resize(static_cast<int>(subset.size()));
  for (size_t k = 0; k < subset.size(); ++k) subset_rows.Set(static_cast<int>(k), s.rows.Rows(subset[k]));
  const CandidateRows& scored = subset.empty() ? s.rows : subset_rows;

  if (s.cached && !criteria.switched) {
    if (s.cache.updates_since_reset() >= 50) {
      s.cache.Reset(s.state, s.rows, s.options.threads, s.sigma_screened);
      s.bounds_current = false;
    }
    if (s.sigma_screened) {  // bounds only, for BestByBounds below
      if (!s.bounds_current) s.cache.SigmaUpperBounds(s.state, &s.sigma_bounds, s.options.threads);
      s.primary_scores.swap(s.sigma_bounds);  // used once: the next exchange writes them anew
      s.bounds_current = false;
    } else {
      s.cache.Growth(&s.primary_scores);  // ranks candidates as the criterion does
    }
  } else {
    ScoreInParallel(s.state, criteria.add, scored, &s.primary_scores, s.options.threads);
  }
  for (int k = 0; k < scored.size(); ++k) {
    if (s.in_plan[candidate_of(k)]) s.primary_scores[k] = kMinusInfinity;
  }
  int pick;
  if (s.sigma_screened) {
    pick = BestByBounds(nullptr, s.primary_scores, s.state, Criterion::kS, scored);
  } else if (criteria.secondary && s.options.screen && IsEigenvalueCriterion(*criteria.secondary)) {
    pick = SelectBestScreened(s.state, *criteria.secondary, scored, s.primary_scores, s.options.keep,
                              s.options.threads);
  } else {
    if (criteria.secondary) ScoreInParallel(s.state, *criteria.secondary, scored, &s.secondary_scores, s.options.threads);
    pick = SelectBest(s.primary_scores, criteria.secondary ? &s.secondary_scores : nullptr, s.options.keep);
  }
  if (pick < 0) return Status::BadInput("every candidate is already in the plan: the candidate set is too small");
  const int index = candidate_of(pick);
  s.in_plan[index] = 1;
  return PlanEntry{s.candidates[index], s.rows.Rows(index), index};
}

// AddFind on the bounded workspace Ω (fig. 2b): U constrained local
// maximisations of C_a(Υ^N + {ζ}) (SLSQP, continuous_addfind.h) from starts
// drawn in the candidate list; ζ+ is the best of their optima.
StatusOr<PlanEntry> AddFindContinuous(Search& s, const AddCriteria& criteria) {
  const int count = static_cast<int>(s.candidates.size());
  std::vector<Vector6d> start_poses;
  for (int k = 0; k < s.starts; ++k) start_poses.push_back(s.candidates[s.rng() % count]);
  const std::vector<ContinuousResult> found =
      ContinuousAddFind(s.model, s.state, criteria.add, start_poses, 100, s.options.threads);
  if (found.empty()) {
    return Status::BadInput("continuous AddFind found no feasible pose from " + std::to_string(s.starts) + " starts");
  }
  s.primary_scores.clear();
  s.secondary_scores.clear();
  for (const ContinuousResult& r : found) {
    s.primary_scores.push_back(r.value);
    if (criteria.secondary) {
      s.secondary_scores.push_back(s.state.ValueAfterAdding(*criteria.secondary, s.model.Rows(r.pose)));
    }
  }
  const int pick = SelectBest(s.primary_scores, criteria.secondary ? &s.secondary_scores : nullptr, s.options.keep);
  if (pick < 0) return Status::Failed("continuous AddFind found no pose with a finite criterion");
  return PlanEntry{found[pick].pose, s.model.Rows(found[pick].pose), s.next_new_id--};
}

// The Tabu step (section 4.3): T = {ζ+_i, ..., ζ+_j} holds the last n added
// poses, which RemoveFind may not drop (fig. 4). n = 0 is the basic IOOPS.
void RememberAdded(int64_t id, int length, std::deque<int64_t>* tabu) {
  if (length == 0) return;
  tabu->push_back(id);
  if (static_cast<int>(tabu->size()) > length) tabu->pop_front();
}

// RemoveFind (fig. 3): ζ- is the ζ of Υ^{N+1} that maximises
// C_r(Υ^{N+1} - {ζ}), C_r the primary criterion; with Tabu (fig. 4) the poses
// in T are left out; with the section 4.2 randomisation, one of the r best
// at random. Returns ζ-'s position in the plan.
int RemoveFind(Search& s) {
  std::vector<std::pair<double, int>> removals;
  for (int k = 0; k < static_cast<int>(s.plan.size()); ++k) {
    if (std::find(s.tabu.begin(), s.tabu.end(), s.plan[k].id) != s.tabu.end()) continue;
    removals.push_back({s.state.ValueAfterRemoving(s.options.criterion, s.plan[k].rows), k});
  }
  std::sort(removals.begin(), removals.end(), std::greater<>());
  const int choices = std::min<int>(s.options.removal_choices, removals.size());
  return removals[choices > 1 ? s.rng() % choices : 0].second;
}

// One iteration of fig. 1: ζ+ = AddFind(Ω, Υ^N, C_a), Υ^{N+1} = Υ^N ∪ ζ+,
// ζ- = RemoveFind(Υ^{N+1}, C_r), Υ^N = Υ^{N+1} - {ζ-}. True when ζ- ≠ ζ+
// (false is the basic algorithm's termination condition, section 4.1.4).
StatusOr<bool> Exchange(Search& s) {
  const AddCriteria criteria = DrawAddCriteria(s.options, s.rng);
  StatusOr<PlanEntry> added = s.options.continuous ? AddFindContinuous(s, criteria) : AddFindFinite(s, criteria);
  if (!added.ok()) return added.status();
  s.plan.push_back(*added);
  std::optional<DesignState> before_add;
  if (s.cached) before_add = s.state;
  s.state.Add(added->rows);
  RememberAdded(added->id, s.options.tabu, &s.tabu);

  const int removed_index = RemoveFind(s);
  const PlanEntry removed = s.plan[removed_index];
  s.plan.erase(s.plan.begin() + removed_index);
  const bool exchanged = removed.id != added->id;
  if (s.cached && exchanged) {
    DesignState after = s.state;
    after.Remove(removed.rows);
    s.cache.Exchanged(*before_add, added->rows, s.state, removed.rows, s.rows, s.options.threads,
                      s.sigma_screened ? &after : nullptr, &s.sigma_bounds);
    s.bounds_current = s.sigma_screened;
    s.state = std::move(after);
  } else {
    s.state.Remove(removed.rows);
  }
  if (removed.id >= 0) s.in_plan[removed.id] = 0;
  return exchanged;
}

// The best plan's unweighted indices (paper section 2) and primary criterion.
void SetFinal(const PlanningModel& model, const PlannerOptions& options, const std::vector<PlanEntry>& best,
              PlanResult* result) {
  result->poses = PosesOf(best);
  result->candidate_indices.clear();
  for (const PlanEntry& entry : best) result->candidate_indices.push_back(std::max<int64_t>(entry.id, -1));
  result->final = PaperIndices(model.robot, best);
  result->final_primary = DesignState::FromRows(RowsOf(best)).Value(options.criterion);
}

}  // namespace

const OptionTable<PlannerOptions>& PlannerOptionSpecs() {
  static const OptionTable<PlannerOptions> table = [] {
    // Each leg's 7 parameters need 7 poses.
    return OptionTable<PlannerOptions>{
        NumberOption<PlannerOptions>("poses", "Poses N", OptionType::kInteger, "poses", kParamsPerLeg, 100000,
                                     "N, the poses in the plan",
                                     [](PlannerOptions& o) -> int& { return o.num_poses; }),
        NumberOption<PlannerOptions>(
            "keep", "Keep on primary", OptionType::kNumber, "fraction", 0.01, 1,
            "section 6.2: fraction of AddFind's results kept on the primary before the secondary picks",
            [](PlannerOptions& o) -> double& { return o.keep; }),
        NumberOption<PlannerOptions>("tabu", "Tabu list n", OptionType::kInteger, "poses", 0, 100000,
                                     "section 4.3: the last n added poses may not be removed; 0 turns Tabu off",
                                     [](PlannerOptions& o) -> int& { return o.tabu; }),
        NumberOption<PlannerOptions>(
            "iterations", "Iteration budget", OptionType::kInteger, "iterations", 0, 1000000,
            "0: 200 with Tabu, else 10 N; the search also stops when a pose is added and removed again",
            [](PlannerOptions& o) -> int& { return o.iterations; }),
        NumberOption<PlannerOptions>(
            "addfind_starts", "AddFind starts U", OptionType::kInteger, "candidates", 0, 10000000,
            "candidates drawn each iteration (0: all of them; continuous: 40 SLSQP starts)",
            [](PlannerOptions& o) -> int& { return o.addfind_starts; }),
        NumberOption<PlannerOptions>(
            "switch_probability", "Criterion switch", OptionType::kNumber, "probability", 0, 1,
            "section 4.2: AddFind uses the secondary criterion with this probability",
            [](PlannerOptions& o) -> double& { return o.criterion_switch_probability; }),
        NumberOption<PlannerOptions>("removal_choices", "Removal choices r", OptionType::kInteger, "poses", 1, 1000,
                                     "section 4.2: RemoveFind drops one of the r least useful poses at random",
                                     [](PlannerOptions& o) -> int& { return o.removal_choices; }),
        SeedOption<PlannerOptions>("random seed of the candidates, the initial set and the randomisation",
                                   [](PlannerOptions& o) -> uint64_t& { return o.seed; }),
        ThreadsOption<PlannerOptions>("Scoring threads", "threads that score candidates; 0 = every core",
                                      [](PlannerOptions& o) -> int& { return o.threads; })};
  }();
  return table;
}

Status PlannerOptions::Check() const {
  if (Status s = CheckOptionRanges(PlannerOptionSpecs(), *this); !s.ok()) return s;
  if (tabu >= num_poses) {
    return Status::BadOption("tabu", "must be shorter than the plan (" + std::to_string(num_poses) + " poses), got " +
                                         std::to_string(tabu));
  }
  if (criterion_switch_probability > 0 && !secondary)
    return Status::BadOption("switch_probability", "needs a secondary criterion to switch to");
  return Status::Ok();
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

// IOOPS (fig. 1): the exchange loop from the initial Υ^N until ζ+ = ζ- (basic)
// or the iteration budget (Tabu); the best plan seen on the selection
// criterion (the secondary if any) is the result.
StatusOr<PlanResult> PlanPoses(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                               const std::vector<Vector6d>& initial, const PlannerOptions& options,
                               const JobHooks& hooks, const PlanIterationObserver& on_iteration) {
  return PlanPoses(model, candidates, nullptr, initial, options, hooks, on_iteration);
}

StatusOr<PlanResult> PlanPoses(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                               const CandidateRows* candidate_rows, const std::vector<Vector6d>& initial,
                               const PlannerOptions& options, const JobHooks& hooks,
                               const PlanIterationObserver& on_iteration) {
  const auto start_time = std::chrono::steady_clock::now();
  if (Status s = CheckPlanInput(candidates, initial, options); !s.ok()) return s;
  if (candidate_rows && !options.continuous && candidate_rows->size() != static_cast<int>(candidates.size())) {
    return Status::BadInput("the candidate rows do not match the candidates");
  }
  Search search(model, candidates, options.continuous ? nullptr : candidate_rows, initial, options);
  if (!search.state.full_rank()) {
    return Status::BadInput(
        "the initial poses do not identify all 42 parameters (a leg's information matrix is "
        "singular): start from more varied poses");
  }

  const Criterion selection = options.secondary.value_or(options.criterion);
  std::vector<PlanEntry> best = search.plan;
  double best_value = search.state.Value(selection);
  PlanResult result;
  auto record = [&](int iteration, bool exchanged) {
    const PlanIteration step{iteration,
                             PaperIndices(model.robot, search.plan),
                             search.state.Value(options.criterion),
                             options.secondary ? search.state.Value(*options.secondary) : 0.0,
                             exchanged,
                             best_value};
    result.history.push_back(step);
    if (on_iteration) on_iteration(step);
  };
  record(0, false);
  result.initial = result.history.back().indices;
  result.initial_primary = result.history.back().primary;

  const int budget = options.IterationBudget();
  for (int iteration = 1; iteration <= budget; ++iteration) {
    if (hooks.Cancelled()) return Status::Cancelled("planning cancelled at iteration " + std::to_string(iteration));
    StatusOr<bool> exchanged = Exchange(search);
    if (!exchanged.ok()) return exchanged.status();
    result.iterations = iteration;
    if (const double value = search.state.Value(selection); value > best_value) {
      best_value = value;
      best = search.plan;
      result.best_iteration = iteration;
    }
    record(iteration, *exchanged);
    hooks.Progress(iteration, budget);
    if (!*exchanged && options.tabu == 0) {
      result.converged = true;
      break;
    }
  }
  SetFinal(model, options, best, &result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace hexcal

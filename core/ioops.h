// IOOPS, the iterative one-by-one pose search (paper section 4, figs 1-4),
// a DETMAX-style exchange: add the pose that most improves the criterion,
// remove the one whose removal keeps it highest, until the same pose is added
// and removed. With the section 4.2 randomisation (criterion switching,
// randomised removal), the section 6.2 primary/secondary criterion (keep the
// best `keep` fraction of the AddFind results on the primary, pick on the
// secondary) and the section 4.3 Tabu list (the last n added poses may not be
// removed; an iteration budget; the best plan seen is returned).
//
// AddFind searches a finite candidate set (all of it, or U drawn at random each
// iteration) or, with `continuous`, the workspace itself: U constrained local
// maximisations (SLSQP, continuous_addfind.h) from starts drawn from the
// candidate list.
//
//   PlannerOptions options;  options.num_poses = 18;
//   StatusOr<PlanResult> plan = PlanPoses(model, candidates, initial, options);
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/observability.h"
#include "core/option_spec.h"
#include "core/planning_model.h"

namespace hexcal {

struct PlannerOptions {
  int num_poses = 18;                     // N
  Criterion criterion = Criterion::kO1;   // primary (AddFind and RemoveFind)
  std::optional<Criterion> secondary;     // section 6.2: chooses among the best `keep` of AddFind
  double keep = 0.8;                      // fraction kept on the primary criterion, 0.01..1
  int tabu = 0;                           // n: last n added poses RemoveFind may not drop (0: off)
  int iterations = 0;                     // budget; 0: 200 with Tabu, else 10 N (stops earlier on add == remove)
  int addfind_starts = 0;                 // U; 0: every candidate (finite) or 40 starts (continuous)
  bool continuous = false;                // AddFind by SLSQP in the workspace
  double criterion_switch_probability = 0;  // section 4.2: AddFind uses the secondary with this probability
  int removal_choices = 1;                // section 4.2: remove one of the r best at random
  uint64_t seed = 1;
  int threads = 0;                        // candidate scoring threads; 0: every core
  // Candidates are screened by upper bounds before their exact values are
  // computed: an eigenvalue secondary (O2-O4, E) before its secular equations,
  // S as the only criterion before its 42 square roots. The choice is the
  // same (ioops_test checks it against the plain scoring of every candidate, false).
  bool screen = true;

  // The ranges of PlannerOptionSpecs, then the rules between options; a
  // failure names the option by its key (Status::BadOption).
  Status Check() const;
  int IterationBudget() const;
};

// The descriptors of the planner's numeric options (`poses`, at least 7, a
// leg's parameters; `keep`, `tabu`, `iterations`, `addfind_starts`,
// `switch_probability`, `removal_choices`, `seed`, `threads`). Check applies
// them, and the plan's option table (workflow/plan_options.h) takes them whole
// for the CLI flags, the settings file and the GUI form.
const OptionTable<PlannerOptions>& PlannerOptionSpecs();

struct PlanIteration {
  int iteration = 0;
  ObservabilityIndices indices;  // of the N-pose plan after this iteration
  double primary = 0, secondary = 0;
  bool exchanged = false;        // false when the added pose was removed again
  double best = 0;               // best so far on the selection criterion (the secondary if set)
};

struct PlanResult {
  std::vector<Vector6d> poses;           // the best plan seen, N poses
  // Per pose, its index in the candidates; -1 for a pose that is not one (a
  // continuous AddFind's, or an initial pose that is no candidate).
  std::vector<int64_t> candidate_indices;
  std::vector<PlanIteration> history;    // iteration 0 is the initial set
  ObservabilityIndices initial, final;   // unweighted indices (paper section 2)
  double initial_primary = 0, final_primary = 0;
  int iterations = 0;
  int best_iteration = 0;
  bool converged = false;                // stopped because the added pose was removed
  double seconds = 0;
};

// Each history entry as it is recorded (iteration 0 first), for live plots of
// the indices (figs 6, 10-12) and of the best value; called on the planning thread.
using PlanIterationObserver = std::function<void(const PlanIteration& step)>;

// `candidates` is the finite search set (and the start list in continuous
// mode); `initial` holds N poses to start from. hooks.Progress(iteration,
// budget) after each iteration; hooks.cancel stops before the next one
// (Status::Cancelled).
StatusOr<PlanResult> PlanPoses(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                               const std::vector<Vector6d>& initial, const PlannerOptions& options,
                               const JobHooks& hooks = {}, const PlanIterationObserver& on_iteration = {});
// The same with the candidates' rows given (model.RowsOf(candidates), shared
// with the certificates); a finite search then does not compute them again.
StatusOr<PlanResult> PlanPoses(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                               const CandidateRows* candidate_rows, const std::vector<Vector6d>& initial,
                               const PlannerOptions& options, const JobHooks& hooks = {},
                               const PlanIterationObserver& on_iteration = {});

// Scores every candidate with DesignState::ScoreAdditions on `threads` threads
// (0: every core); the scores do not depend on the thread count.
void ScoreInParallel(const DesignState& state, Criterion criterion, const CandidateRows& candidates,
                     std::vector<double>* scores, int threads);

}  // namespace hexcal

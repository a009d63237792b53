// The section 8 study: RunSubsetStudy draws the subsets, SelectByIoops is the
// paper's selection among the measured poses, EvaluateSubset one calibration
// and its held-out validation (Table 5's two columns for one subset).
#include "core/subset_study.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "core/error_stats.h"
#include "core/ioops.h"
#include "core/observability.h"
#include "core/parallel.h"
#include "core/planning_model.h"
#include "core/validation.h"

namespace hexcal {
namespace {

// Streams of random numbers, one per use, so that adding random subsets never
// changes the IOOPS start and the reverse.
constexpr uint64_t kSubsetStream = 0x5ab5e75;
constexpr uint64_t kStartStream = 0x10095;
// Draws of an IOOPS start before giving up on finding one that identifies all 42 parameters.
constexpr int kStartDraws = 20;

// N distinct indices of 0 .. M − 1, ascending: a partial Fisher–Yates shuffle.
std::vector<int> DrawSubset(int total, int size, std::mt19937_64* rng) {
  std::vector<int> all(total);
  std::iota(all.begin(), all.end(), 0);
  for (int k = 0; k < size; ++k) {
    std::uniform_int_distribution<int> pick(k, total - 1);
    std::swap(all[k], all[pick(*rng)]);
  }
  std::vector<int> subset(all.begin(), all.begin() + size);
  std::sort(subset.begin(), subset.end());
  return subset;
}

std::vector<PoseRows> RowsOfSubset(const std::vector<PoseRows>& rows, const std::vector<int>& subset) {
  std::vector<PoseRows> chosen;
  for (int j : subset) chosen.push_back(rows[j]);
  return chosen;
}

// O1..O4 (observability.h) from the stored rows: M_i = Σ_j r_ij r_ijᵀ.
ObservabilityIndices IndicesOfSubset(const std::vector<PoseRows>& rows, const std::vector<int>& subset) {
  InformationBlocks info;
  for (int j : subset) {
    for (int i = 0; i < kNumLegs; ++i) info.blocks[i].noalias() += rows[j][i].transpose() * rows[j][i];
  }
  info.num_poses = static_cast<int>(subset.size());
  return ComputeIndices(info);
}

// An initial subset whose information matrices are all invertible (IOOPS refuses a singular start).
StatusOr<std::vector<int>> DrawStart(const std::vector<PoseRows>& rows, int size, std::mt19937_64* rng) {
  for (int draw = 0; draw < kStartDraws; ++draw) {
    std::vector<int> start = DrawSubset(static_cast<int>(rows.size()), size, rng);
    if (DesignState::FromRows(RowsOfSubset(rows, start)).full_rank()) return start;
  }
  return Status::Failed("no " + std::to_string(size) + " of the " + std::to_string(rows.size()) +
                        " measured poses drawn at random identify all 42 parameters (" + std::to_string(kStartDraws) +
                        " draws): the poses are too alike");
}

struct Selection {
  std::vector<int> poses;
  int iterations = 0;
};

// IOOPS (ioops.h) among the measured poses, from `selection_starts` random
// starts; the plan best on the selection criterion (the secondary when set) wins.
StatusOr<Selection> SelectByIoops(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                                  const std::vector<PoseRows>& rows, const SubsetStudyOptions& options,
                                  const JobHooks& hooks) {
  std::mt19937_64 rng(options.seed ^ kStartStream);
  const Criterion judge = options.secondary.value_or(options.criterion);
  Selection best;
  double best_value = -std::numeric_limits<double>::infinity();
  for (int start = 0; start < options.selection_starts; ++start) {
    StatusOr<std::vector<int>> initial = DrawStart(rows, options.select, &rng);
    if (!initial.ok()) return initial.status();
    std::vector<Vector6d> initial_poses;
    for (int j : *initial) initial_poses.push_back(candidates[j]);
    PlannerOptions planner;
    planner.num_poses = options.select;
    planner.criterion = options.criterion;
    planner.secondary = options.secondary;
    planner.seed = options.seed + static_cast<uint64_t>(start);
    planner.threads = options.num_threads;
    StatusOr<PlanResult> plan = PlanPoses(model, candidates, initial_poses, planner, {nullptr, hooks.cancel});
    if (!plan.ok()) return plan.status();
    // A finite IOOPS started from candidates holds candidates only.
    std::vector<int> chosen(plan->candidate_indices.begin(), plan->candidate_indices.end());
    std::sort(chosen.begin(), chosen.end());
    const double value = DesignState::FromRows(RowsOfSubset(rows, chosen)).Value(judge);
    if (value > best_value) {
      best_value = value;
      best = {std::move(chosen), plan->iterations};
    }
  }
  return best;
}

Status CheckStudyInput(const std::vector<Measurement>& measurements, const SubsetStudyOptions& options) {
  if (Status s = options.Check(); !s.ok()) return s;
  const int total = static_cast<int>(measurements.size());
  if (options.select >= total) {
    return Status::BadOption("select", std::to_string(options.select) + " needs more than that many measured poses " +
                                           "(some must be left out to validate); the session has " +
                                           std::to_string(total));
  }
  return Status::Ok();
}

}  // namespace

const OptionTable<SubsetStudyOptions>& SubsetStudyOptionSpecs() {
  static const OptionTable<SubsetStudyOptions> table = [] {
    using Options = SubsetStudyOptions;
    // Each leg's 7 parameters need 7 poses.
    return OptionTable<Options>{
        NumberOption<Options>("select", "Poses per subset (N)", OptionType::kInteger, "poses", kParamsPerLeg, 100000,
                              "poses in the selected and in each random subset (the paper's 13); fewer than the "
                              "session's measured poses",
                              [](Options& o) -> int& { return o.select; }),
        NumberOption<Options>("subsets", "Random subsets (K)", OptionType::kInteger, "", 1, 1000000,
                              "random subsets of N poses the selected one is ranked against (the paper's 6000)",
                              [](Options& o) -> int& { return o.subsets; }),
        NumberOption<Options>("starts", "IOOPS starts", OptionType::kInteger, "", 1, 1000,
                              "IOOPS runs from this many random initial subsets; the best on the criterion is kept",
                              [](Options& o) -> int& { return o.selection_starts; }),
        SeedOption<Options>("seed of the IOOPS starts and the random subsets; the numbers do not depend on the threads",
                            [](Options& o) -> uint64_t& { return o.seed; }),
        ThreadsOption<Options>("Threads", "subsets calibrated at once; 0 = every core",
                               [](Options& o) -> int& { return o.num_threads; })};
  }();
  return table;
}

Status SubsetStudyOptions::Check() const {
  if (Status s = CheckOptionRanges(SubsetStudyOptionSpecs(), *this); !s.ok()) return s;
  std::string error;
  if (!calibration.IsValid(&error)) return Status::BadInput(error);
  return Status::Ok();
}

SubsetOutcome EvaluateSubset(const Robot& nominal, const std::vector<Measurement>& measurements,
                             const std::vector<int>& poses, const CalibrationOptions& calibration) {
  SubsetOutcome outcome;
  outcome.poses = poses;
  std::vector<char> chosen(measurements.size(), 0);
  for (int j : poses) chosen[j] = 1;
  std::vector<Measurement> fit, held_out;
  for (size_t j = 0; j < measurements.size(); ++j) (chosen[j] ? fit : held_out).push_back(measurements[j]);
  StatusOr<CalibrationResult> calibrated = Calibrate(nominal, fit, calibration);
  if (!calibrated.ok()) {
    outcome.failure = "calibration: " + calibrated.status().message();
    return outcome;
  }
  StatusOr<ValidationReport> validation = Validate(calibrated->robot, held_out);
  if (!validation.ok()) {
    outcome.failure = "validation: " + validation.status().message();
    return outcome;
  }
  outcome.ok = true;
  outcome.heldout_position_rms = validation->position.rms;
  outcome.heldout_orientation_rms_deg = validation->orientation_deg.rms;
  outcome.heldout_fk_failed = validation->failed;
  return outcome;
}

StatusOr<SubsetStudyResult> RunSubsetStudy(const Robot& nominal, const std::vector<Measurement>& measurements,
                                           const SubsetStudyOptions& options, const JobHooks& hooks) {
  if (Status s = CheckStudyInput(measurements, options); !s.ok()) return s;
  const PlanningModel paper_model{nominal, std::nullopt, std::nullopt};  // the unweighted J_P of the indices
  const PlanningModel selection_model{nominal, options.selection_noise, std::nullopt};
  std::vector<Vector6d> candidates;
  std::vector<PoseRows> rows, selection_rows;
  for (const Measurement& m : measurements) {
    candidates.push_back(m.pose);
    rows.push_back(paper_model.Rows(m.pose));
    selection_rows.push_back(options.selection_noise ? selection_model.Rows(m.pose) : rows.back());
  }
  hooks.Stage("select (IOOPS)");
  StatusOr<Selection> selection = SelectByIoops(selection_model, candidates, selection_rows, options, hooks);
  if (!selection.ok()) return selection.status();

  const int total = static_cast<int>(measurements.size());
  std::vector<std::vector<int>> subsets = {selection->poses};
  std::mt19937_64 rng(options.seed ^ kSubsetStream);
  for (int k = 0; k < options.subsets; ++k) subsets.push_back(DrawSubset(total, options.select, &rng));

  CalibrationOptions calibration = options.calibration;
  calibration.compute_uncertainty = false;
  calibration.num_threads = 1;
  std::vector<SubsetOutcome> outcomes(subsets.size());
  hooks.Stage("calibrate and validate subsets");
  const bool finished = ParallelFor(
      static_cast<int>(subsets.size()), options.num_threads,
      [&](int k, int) {
        outcomes[k] = EvaluateSubset(nominal, measurements, subsets[k], calibration);
        outcomes[k].indices = IndicesOfSubset(rows, subsets[k]);
      },
      hooks);
  if (!finished || hooks.Cancelled()) return Status::Cancelled();

  SubsetStudyResult result;
  result.measurements = total;
  result.selected = std::move(outcomes[0]);
  result.selection_iterations = selection->iterations;
  result.random.assign(std::make_move_iterator(outcomes.begin() + 1), std::make_move_iterator(outcomes.end()));
  for (size_t k = 0; k < result.random.size(); ++k) {
    if (result.random[k].ok) continue;
    if (result.failed++ == 0)
      result.first_failure = "subset " + std::to_string(k + 1) + ": " + result.random[k].failure;
  }
  if (result.failed == options.subsets)
    return Status::Failed("every random subset failed; first: " + result.first_failure);
  return result;
}

const char* SubsetMetricName(SubsetMetric metric) {
  switch (metric) {
    case SubsetMetric::kO1:
      return "O1";
    case SubsetMetric::kO2:
      return "O2";
    case SubsetMetric::kO3:
      return "O3";
    case SubsetMetric::kO4:
      return "O4";
    case SubsetMetric::kHeldOutPosition:
      return "heldout_position_rms";
    case SubsetMetric::kHeldOutOrientation:
      return "heldout_orientation_rms";
  }
  return "";
}

std::string SubsetMetricLabel(SubsetMetric metric, const std::string& length_unit) {
  switch (metric) {
    case SubsetMetric::kHeldOutPosition:
      return "held-out position RMS (" + length_unit + ")";
    case SubsetMetric::kHeldOutOrientation:
      return "held-out orientation RMS (deg)";
    default: {
      // O1..O4 with their unit (issue 39): O2 is a ratio, the others lengths.
      const int k = static_cast<int>(metric) - static_cast<int>(SubsetMetric::kO1) + 1;
      const std::string unit = IndexUnit(k, length_unit);
      return std::string(SubsetMetricName(metric)) + " (" + (unit.empty() ? "a ratio" : unit) + ")";
    }
  }
}

bool HigherIsBetter(SubsetMetric metric) {
  return metric != SubsetMetric::kHeldOutPosition && metric != SubsetMetric::kHeldOutOrientation;
}

double MetricValue(const SubsetOutcome& outcome, SubsetMetric metric) {
  switch (metric) {
    case SubsetMetric::kO1:
      return outcome.indices.o1;
    case SubsetMetric::kO2:
      return outcome.indices.o2;
    case SubsetMetric::kO3:
      return outcome.indices.o3;
    case SubsetMetric::kO4:
      return outcome.indices.o4;
    case SubsetMetric::kHeldOutPosition:
      return outcome.heldout_position_rms;
    case SubsetMetric::kHeldOutOrientation:
      return outcome.heldout_orientation_rms_deg;
  }
  return 0;
}

std::vector<double> RandomValues(const SubsetStudyResult& result, SubsetMetric metric) {
  std::vector<double> values;
  for (const SubsetOutcome& outcome : result.random) {
    if (outcome.ok || HigherIsBetter(metric)) values.push_back(MetricValue(outcome, metric));
  }
  return values;
}

Distribution SummarizeDistribution(std::vector<double> values) {
  Distribution d;
  d.count = static_cast<int>(values.size());
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  const auto percentile = [&](double p) {
    const double position = p / 100 * (values.size() - 1);
    const size_t below = static_cast<size_t>(std::floor(position));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - below) * (values[above] - values[below]);
  };
  d.min = values.front();
  d.max = values.back();
  d.p5 = percentile(5);
  d.p25 = percentile(25);
  d.median = percentile(50);
  d.p75 = percentile(75);
  d.p95 = percentile(95);
  const ErrorStats stats = SummarizeErrors(values);  // mean and sample std
  d.mean = stats.mean;
  d.std = stats.std;
  return d;
}

double PercentBeaten(const std::vector<double>& values, double x, bool higher_is_better) {
  if (values.empty()) return 0;
  double beaten = 0;
  for (double v : values) {
    if (v == x) {
      beaten += 0.5;
    } else if (higher_is_better ? v < x : v > x) {
      beaten += 1;
    }
  }
  return 100 * beaten / static_cast<double>(values.size());
}

}  // namespace hexcal

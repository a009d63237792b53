// The real-robot study of the paper's section 8 (Figs. 18, 19, Table 5;
// docs/calibration.md, "The section 8 study"): among M measured poses, IOOPS
// selects N; that subset and K random N-subsets are each calibrated (the
// implicit per-leg least squares of calibration.h, from the nominal robot)
// and validated by forward kinematics on the M − N poses each leaves out
// (validation.h). The question: where does the selected subset rank among
// random subsets of its size, on the observability indices O1..O4 (Fig. 18)
// and on the held-out pose error (Fig. 19, Table 5)?
//
// The measurements are platform poses in the base frame with their readings
// (a session's board poses through the registered frames, registration.h).
// The selection is IOOPS (ioops.h) with the measured poses as the finite
// candidate set, started from N measured poses drawn from the seed, on the
// nominal robot's rows: unweighted (the paper's J_P; section 8 optimised O4)
// or divided by each residual's noise (selection_noise, the CLI's default
// with O1: it validates better, docs/calibration.md).
// The K random subsets are drawn from the seed before any work, so the
// result does not depend on the thread count.
//
//   SubsetStudyOptions options;  // N = 13, K = 6000, O1
//   StatusOr<SubsetStudyResult> study = RunSubsetStudy(nominal, measurements, options, hooks);
//   double beaten = PercentBeaten(RandomValues(*study, SubsetMetric::kHeldOutPosition),
//                                 study->selected.heldout_position_rms, /*higher_is_better=*/false);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/design_criteria.h"
#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/observability.h"
#include "core/option_spec.h"

namespace hexcal {

struct SubsetStudyOptions {
  int select = 13;                       // N, poses per subset: at least 7, fewer than the measurements
  int subsets = 6000;                    // K random subsets (the paper's 6000)
  Criterion criterion = Criterion::kO1;  // IOOPS's primary criterion (section 8 optimised O4; docs/calibration.md)
  std::optional<Criterion> secondary;    // section 6.2's secondary criterion; none in section 8
  // IOOPS runs from this many random initial subsets; the selection with the
  // best value of the criterion (the secondary when set) is kept.
  int selection_starts = 1;
  // IOOPS's rows divided by the standard deviation of their residual under
  // this noise model (planning_model.h, beyond the paper); none: the paper's
  // unweighted J_P. The reported indices O1..O4 are always unweighted.
  std::optional<NoiseModel> selection_noise;
  uint64_t seed = 1;  // of the initial subsets and the random subsets
  // Each subset's calibration. It runs single-threaded and without the
  // uncertainty report: the subsets are what is spread over the cores.
  CalibrationOptions calibration;
  int num_threads = 0;  // subsets at once; 0 = every core

  // The ranges of SubsetStudyOptionSpecs(), then the calibration's options;
  // a range error names the option by its key (Status::option()).
  Status Check() const;
};

// The descriptors of select, subsets, starts, seed and threads: Check()
// checks them, and the study's option table (workflow/study_options.h) takes
// them whole for the CLI flags and the GUI form.
const OptionTable<SubsetStudyOptions>& SubsetStudyOptionSpecs();

// One subset, calibrated and validated on the measurements it leaves out.
struct SubsetOutcome {
  std::vector<int> poses;        // indices into the measurements, ascending
  ObservabilityIndices indices;  // O1..O4 of the subset (nominal robot, unweighted rows)
  bool ok = false;               // calibrated, and FK converged on at least one held-out pose
  std::string failure;           // why not, when !ok
  // RMS over the held-out poses FK converged on of |P_fk − P_measured| (robot
  // unit) and of the rotation angle between R_fk and R_measured (degrees).
  double heldout_position_rms = 0;
  double heldout_orientation_rms_deg = 0;
  int heldout_fk_failed = 0;  // held-out poses where FK did not converge
};

struct SubsetStudyResult {
  int measurements = 0;    // M
  SubsetOutcome selected;  // IOOPS's subset
  int selection_iterations = 0;
  std::vector<SubsetOutcome> random;  // K, in the order drawn
  int failed = 0;                     // random subsets that are not ok
  std::string first_failure;          // the first of them in draw order, "subset k: why"
};

// hooks.Stage("select (IOOPS)") then "calibrate and validate subsets" with
// Progress(done, K + 1); hooks.cancel stops the study (Status::Cancelled).
// Fails for bad options, too few measurements, an IOOPS start that cannot
// identify the 42 parameters; a subset whose calibration fails is counted in
// `failed`, and the study fails only when every random subset does.
StatusOr<SubsetStudyResult> RunSubsetStudy(const Robot& nominal, const std::vector<Measurement>& measurements,
                                           const SubsetStudyOptions& options, const JobHooks& hooks = {});

// Calibrates `poses` (indices into measurements) from the nominal robot and
// validates the calibrated robot on the other measurements.
SubsetOutcome EvaluateSubset(const Robot& nominal, const std::vector<Measurement>& measurements,
                             const std::vector<int>& poses, const CalibrationOptions& calibration);

enum class SubsetMetric { kO1, kO2, kO3, kO4, kHeldOutPosition, kHeldOutOrientation };
// Every metric, in that order: the rows of the study's summary (Figs. 18, 19).
constexpr SubsetMetric kSubsetMetrics[] = {SubsetMetric::kO1,
                                           SubsetMetric::kO2,
                                           SubsetMetric::kO3,
                                           SubsetMetric::kO4,
                                           SubsetMetric::kHeldOutPosition,
                                           SubsetMetric::kHeldOutOrientation};
const char* SubsetMetricName(SubsetMetric metric);  // "O1", ..., "heldout_position_rms", "heldout_orientation_rms"
// What a person reads: "O1 (cm)", "O2 (a ratio)", ..., "held-out position RMS (cm)", "held-out orientation RMS (deg)".
std::string SubsetMetricLabel(SubsetMetric metric, const std::string& length_unit);
bool HigherIsBetter(SubsetMetric metric);           // the indices; the errors are better lower
double MetricValue(const SubsetOutcome& outcome, SubsetMetric metric);
// The metric over the random subsets that are ok (the indices over every random subset).
std::vector<double> RandomValues(const SubsetStudyResult& result, SubsetMetric metric);

// A distribution as Table 5 and Figs. 18-19 summarise it. Percentiles by
// linear interpolation between order statistics (p-th of n sorted values at
// position p/100 · (n − 1)); std is the sample standard deviation.
struct Distribution {
  int count = 0;
  double min = 0, p5 = 0, p25 = 0, median = 0, p75 = 0, p95 = 0, max = 0;
  double mean = 0, std = 0;
};
Distribution SummarizeDistribution(std::vector<double> values);

// The percentage of `values` that `x` beats (lies below, when lower is better;
// above, when higher is better), ties counting half; 0 for no values.
double PercentBeaten(const std::vector<double>& values, double x, bool higher_is_better);

}  // namespace hexcal

// The validation experiment of the paper's section 7 (Figs. 14 and 15): how
// well does each pose set let the implicit calibration recover a robot?
//
// 1. A virtual true robot: every one of the 42 nominal parameters plus an
//    independent uniform perturbation in [-perturb, perturb] (robot unit).
// 2. In each run and for each pose set, the measurements the true robot would
//    give: readings L = IK_true(X) at each pose X, then uniform noise on the
//    pose (x, y, z in the robot unit, q1..q3 in degrees) and on each reading.
// 3. Calibration from the nominal parameters (calibration.h), and the error
//    |P_est - P_true| of each of the 42 parameters.
// The error of a set is the mean and standard deviation of those values over
// the 42 parameters and all runs (the error of one calibration, Fig. 14);
// "before" is |P_nominal - P_true| over the 42 parameters.
//
// A random set draws `count` feasible poses (GenerateCandidates, kind random,
// for the nominal robot) afresh in every run; a fixed set (the boundary poses, a
// plan) is measured anew in every run. Every random number comes from a
// generator seeded by (seed, run, set name), so the same seed gives the same
// numbers whatever the thread count and whichever other sets are listed.
//
//   std::vector<SimulationPoseSet> sets = {RandomPoseSet(18), FixedPoseSet("boundary", boundary_poses)};
//   SimulationOptions options;  // 100 runs, ±0.5, the paper's noise
//   StatusOr<SimulationResult> result = Simulate(nominal, sets, options);
//   // result->sets[1].mean, result->sets[1].ratio_to_random
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/error_stats.h"
#include "core/job_hooks.h"
#include "core/option_spec.h"

namespace hexcal {

struct SimulationPoseSet {
  std::string name;
  bool random = false;          // draw `count` feasible random poses in each run
  int count = 0;                // random: poses per run
  std::vector<Vector6d> poses;  // fixed: [x, y, z, q1, q2, q3], robot unit and degrees
  // random: draw in this box instead of the robot's sampling box (still within its pose box).
  std::optional<PoseBox> box;

  int Size() const { return random ? count : static_cast<int>(poses.size()); }
};

SimulationPoseSet RandomPoseSet(int count, const std::string& name = "random");
SimulationPoseSet FixedPoseSet(const std::string& name, std::vector<Vector6d> poses);

struct SimulationOptions {
  int runs = 100;
  uint64_t seed = 1;
  double perturb = 0.5;  // half-width of the uniform perturbation of each parameter, robot unit
  NoiseModel noise;      // measurement noise, uniform; the paper's levels by default
  // The calibration of each run. Its uncertainty report is not computed, and it
  // runs single-threaded: the runs are what is spread over the cores.
  CalibrationOptions calibration;
  int num_threads = 0;  // runs at once; 0 = every core

  // The ranges of SimulationOptionSpecs(), then the noise and the
  // calibration; a range error names the option by its key (Status::option()).
  Status Check() const;
};

// The descriptors of runs, seed, perturb and threads: Check() checks them,
// and `hexcal simulate`'s option table (workflow/simulate_options.h) takes
// them whole.
const OptionTable<SimulationOptions>& SimulationOptionSpecs();

// Fig. 15's numbers of poses MIN..MAX: whole numbers with
// 7 <= MIN <= MAX <= kMaxSweepPoses (each n is one more calibration per run).
constexpr int kMaxSweepPoses = 10000;
bool IsSweepRange(double min_poses, double max_poses);
// "7 <= MIN <= MAX <= 10000", for the messages about a sweep.
std::string SweepRangeRule();

struct SetError {
  std::string name;
  int poses = 0;
  double mean = 0;  // of |P_est - P_true| over the 42 parameters and the successful runs, robot unit
  double std = 0;
  // |mean over runs of P_est - P_true|, averaged over the 42 parameters: the bias left when runs are averaged.
  double mean_estimate_error = 0;
  int runs = 0;         // successful calibrations
  int failed_runs = 0;  // calibrations that failed (degenerate draw, no convergence); not in the statistics
  std::string first_failure;
  std::optional<double> ratio_to_random;  // mean / mean of the first random set, when there is one
};

struct SimulationResult {
  ParameterVector true_parameters;
  ErrorStats before;  // |P_nominal - P_true| over the 42 parameters
  std::vector<SetError> sets;
};

// Fig. 15: the error against the number of poses n = min_poses..max_poses. A
// random set draws max_poses poses per run and uses the first n; a fixed set
// uses its first n poses (and is left out for n above its size). Measurements
// are nested the same way, so consecutive n differ by one pose, not by a new draw.
struct SweepPoint {
  int poses = 0;
  std::vector<SetError> sets;  // the sets with at least `poses` poses, in input order
};

struct SweepResult {
  ErrorStats before;
  std::vector<SweepPoint> points;
};

// hooks.Progress(runs_done, runs) from the worker threads, one call at a time;
// hooks.cancel stops the study (Status::Cancelled).
StatusOr<SimulationResult> Simulate(const Robot& nominal, const std::vector<SimulationPoseSet>& sets,
                                    const SimulationOptions& options, const JobHooks& hooks = {});

StatusOr<SweepResult> SimulateSweep(const Robot& nominal, const std::vector<SimulationPoseSet>& sets, int min_poses,
                                    int max_poses, const SimulationOptions& options, const JobHooks& hooks = {});

// The true robot of a simulation: the nominal one perturbed as in step 1.
Robot PerturbedRobot(const Robot& nominal, double perturb, uint64_t seed);

// Step 2 for one list of true poses, noise drawn from `rng`.
std::vector<Measurement> SimulateMeasurements(const Robot& true_robot, const std::vector<Vector6d>& poses,
                                              const NoiseModel& noise, std::mt19937_64* rng);

}  // namespace hexcal

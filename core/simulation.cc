#include "core/simulation.h"

#include <algorithm>
#include <cmath>

#include "core/candidates.h"
#include "core/parallel.h"

namespace hexcal {
namespace {

// splitmix64's finaliser: a bijective scramble, so different inputs give unrelated seeds.
uint64_t Scramble(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// FNV-1a: stable across compilers and runs, unlike std::hash.
uint64_t NameHash(const std::string& name) {
  uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : name) hash = (hash ^ c) * 0x100000001b3ULL;
  return hash;
}

enum Stream : uint64_t { kTruthStream = 1, kPoseStream = 2, kNoiseStream = 3 };

uint64_t StreamSeed(uint64_t seed, uint64_t run, const std::string& set, Stream stream) {
  return Scramble(Scramble(Scramble(Scramble(seed) ^ run) ^ NameHash(set)) ^ stream);
}

// sizes[point][set]: how many poses of each set one calibration of that point uses (0: none).
using StudySizes = std::vector<std::vector<int>>;

// One calibration's outcome: the estimate, or why it failed.
struct RunOutcome {
  std::optional<ParameterVector> estimate;
  std::string failure;
};
// outcomes[point][set][run]
using Outcomes = std::vector<std::vector<std::vector<RunOutcome>>>;

StatusOr<std::vector<Vector6d>> PosesOfRun(const Robot& nominal, const SimulationPoseSet& set, int count,
                                           uint64_t seed) {
  if (!set.random) return std::vector<Vector6d>(set.poses.begin(), set.poses.begin() + count);
  CandidateOptions candidates;
  candidates.kind = CandidateKind::kRandom;
  candidates.count = count;
  candidates.seed = seed;
  Robot sampler = nominal;
  if (set.box) sampler.limits.sampling_box = set.box;  // intersected with the pose box by SamplingBox()
  StatusOr<CandidateSet> drawn = GenerateCandidates(sampler, candidates);
  if (!drawn.ok()) {  // keep the kind: a robot without a pose box is bad input, a box too tight a failure
    const std::string message = "pose set '" + set.name + "': " + drawn.status().message();
    return drawn.status().kind() == StatusKind::kBadInput ? Status::BadInput(message) : Status::Failed(message);
  }
  return std::move(drawn->poses);
}

// Runs every calibration of one run; a returned error (a pose set that cannot
// be drawn, a cancel) stops the whole study, a failed calibration does not.
Status RunOnce(const Robot& nominal, const Robot& true_robot, const std::vector<SimulationPoseSet>& sets,
               const StudySizes& sizes, const SimulationOptions& options, int run, const std::atomic<bool>* cancel,
               Outcomes* outcomes) {
  CalibrationOptions calibration = options.calibration;
  calibration.compute_uncertainty = false;
  calibration.num_threads = 1;
  for (size_t s = 0; s < sets.size(); ++s) {
    int largest = 0;
    for (const auto& point : sizes) largest = std::max(largest, point[s]);
    if (largest == 0) continue;
    StatusOr<std::vector<Vector6d>> poses =
        PosesOfRun(nominal, sets[s], largest, StreamSeed(options.seed, run, sets[s].name, kPoseStream));
    if (!poses.ok()) return poses.status();
    std::mt19937_64 rng(StreamSeed(options.seed, run, sets[s].name, kNoiseStream));
    const std::vector<Measurement> measurements = SimulateMeasurements(true_robot, *poses, options.noise, &rng);
    for (size_t p = 0; p < sizes.size(); ++p) {
      const int n = sizes[p][s];
      if (n == 0) continue;
      const std::vector<Measurement> first_n(measurements.begin(), measurements.begin() + n);
      StatusOr<CalibrationResult> result = Calibrate(nominal, first_n, calibration, {nullptr, cancel});
      RunOutcome& outcome = (*outcomes)[p][s][run];
      if (result.ok()) {
        outcome.estimate = result->Estimates();
      } else if (result.status().cancelled()) {
        return result.status();
      } else {
        outcome.failure = result.status().message();
      }
    }
  }
  return Status::Ok();
}

StatusOr<SetError> Summarize(const SimulationPoseSet& set, int poses, const ParameterVector& truth,
                             const std::vector<RunOutcome>& runs) {
  SetError error;
  error.name = set.name;
  error.poses = poses;
  std::vector<double> values;
  ParameterVector sum = ParameterVector::Zero();
  for (const RunOutcome& run : runs) {
    if (!run.estimate) {
      if (error.failed_runs++ == 0) error.first_failure = run.failure;
      continue;
    }
    ++error.runs;
    sum += *run.estimate;
    for (int k = 0; k < kNumParams; ++k) values.push_back(std::abs((*run.estimate)[k] - truth[k]));
  }
  if (error.runs == 0) {
    return Status::Failed("pose set '" + set.name + "' with " + std::to_string(poses) +
                          " poses: the calibration failed in every run; first: " + error.first_failure);
  }
  const ErrorStats stats = SummarizeErrors(values);
  error.mean = stats.mean;
  error.std = stats.std;
  error.mean_estimate_error = (sum / error.runs - truth).cwiseAbs().mean();
  return error;
}

ErrorStats BeforeCalibration(const Robot& nominal, const Robot& true_robot) {
  const ParameterVector difference = (ParametersOf(nominal) - ParametersOf(true_robot)).cwiseAbs();
  return SummarizeErrors(std::vector<double>(difference.data(), difference.data() + kNumParams));
}

Status CheckSets(const std::vector<SimulationPoseSet>& sets) {
  if (sets.empty()) return Status::BadInput("the simulation needs at least one pose set");
  for (size_t s = 0; s < sets.size(); ++s) {
    if (sets[s].Size() < kParamsPerLeg) {
      return Status::BadInput("pose set '" + sets[s].name + "' has " + std::to_string(sets[s].Size()) +
                              " poses; a calibration needs at least 7");
    }
    for (size_t t = 0; t < s; ++t) {
      if (sets[t].name == sets[s].name) return Status::BadInput("pose set '" + sets[s].name + "' is listed twice");
    }
  }
  return Status::Ok();
}

// The study behind Simulate and SimulateSweep: every run of every point, then
// one SetError per (point, set) with a non-zero size.
StatusOr<std::vector<std::vector<SetError>>> RunStudy(const Robot& nominal, const Robot& true_robot,
                                                      const std::vector<SimulationPoseSet>& sets,
                                                      const StudySizes& sizes, const SimulationOptions& options,
                                                      const JobHooks& hooks) {
  Outcomes outcomes(sizes.size(),
                    std::vector<std::vector<RunOutcome>>(sets.size(), std::vector<RunOutcome>(options.runs)));
  std::vector<Status> run_status(options.runs);
  const bool finished = ParallelFor(
      options.runs, options.num_threads,
      [&](int run, int) {
        run_status[run] = RunOnce(nominal, true_robot, sets, sizes, options, run, hooks.cancel, &outcomes);
      },
      hooks);
  if (!finished || hooks.Cancelled()) return Status::Cancelled();
  for (const Status& status : run_status) {
    if (!status.ok()) return status;
  }
  const ParameterVector truth = ParametersOf(true_robot);
  std::vector<std::vector<SetError>> errors(sizes.size());
  for (size_t p = 0; p < sizes.size(); ++p) {
    std::optional<double> random_mean;  // of the first random set
    for (size_t s = 0; s < sets.size(); ++s) {
      if (sizes[p][s] == 0) continue;
      StatusOr<SetError> error = Summarize(sets[s], sizes[p][s], truth, outcomes[p][s]);
      if (!error.ok()) return error.status();
      if (sets[s].random && !random_mean) random_mean = error->mean;
      errors[p].push_back(std::move(*error));
    }
    if (random_mean && *random_mean > 0) {
      for (SetError& error : errors[p]) error.ratio_to_random = error.mean / *random_mean;
    }
  }
  return errors;
}

}  // namespace

SimulationPoseSet RandomPoseSet(int count, const std::string& name) {
  SimulationPoseSet set;
  set.name = name;
  set.random = true;
  set.count = count;
  return set;
}

SimulationPoseSet FixedPoseSet(const std::string& name, std::vector<Vector6d> poses) {
  SimulationPoseSet set;
  set.name = name;
  set.poses = std::move(poses);
  return set;
}

const OptionTable<SimulationOptions>& SimulationOptionSpecs() {
  static const OptionTable<SimulationOptions> table = [] {
    using Options = SimulationOptions;
    return OptionTable<Options>{
        NumberOption<Options>("runs", "Runs", OptionType::kInteger, "", 1, 1000000,
                              "repetitions: a true robot's measurements drawn anew and calibrated, per set",
                              [](Options& o) -> int& { return o.runs; }),
        SeedOption<Options>(
            "seed of the true robot, the random poses and the noise; the numbers do not depend on the threads",
            [](Options& o) -> uint64_t& { return o.seed; }),
        NumberOption<Options>("perturb", "Perturbation", OptionType::kNumber, "robot unit", 0, 1000000,
                              "half-width of the uniform perturbation of each of the 42 parameters (the true robot)",
                              [](Options& o) -> double& { return o.perturb; }),
        ThreadsOption<Options>("Threads", "runs at once; 0 = every core",
                               [](Options& o) -> int& { return o.num_threads; })};
  }();
  return table;
}

Status SimulationOptions::Check() const {
  if (Status s = CheckOptionRanges(SimulationOptionSpecs(), *this); !s.ok()) return s;
  std::string error;
  if (!noise.IsValid(&error) || !calibration.IsValid(&error)) return Status::BadInput(error);
  return Status::Ok();
}

bool IsSweepRange(double min_poses, double max_poses) {
  return min_poses >= kParamsPerLeg && max_poses >= min_poses && max_poses <= kMaxSweepPoses &&
         min_poses == std::floor(min_poses) && max_poses == std::floor(max_poses);
}

std::string SweepRangeRule() {
  return std::to_string(kParamsPerLeg) + " <= MIN <= MAX <= " + std::to_string(kMaxSweepPoses);
}

Robot PerturbedRobot(const Robot& nominal, double perturb, uint64_t seed) {
  std::mt19937_64 rng(StreamSeed(seed, 0, "", kTruthStream));
  std::uniform_real_distribution<double> offset(-perturb, perturb);
  ParameterVector parameters = ParametersOf(nominal);
  for (int k = 0; k < kNumParams; ++k) parameters[k] += offset(rng);
  return WithParameters(nominal, parameters);
}

std::vector<Measurement> SimulateMeasurements(const Robot& true_robot, const std::vector<Vector6d>& poses,
                                              const NoiseModel& noise, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<Measurement> measurements;
  measurements.reserve(poses.size());
  for (const Vector6d& pose : poses) {
    Measurement m;
    m.legs = InverseKinematics(true_robot, true_robot.PoseFromVector(pose));
    m.pose = pose;
    for (int k = 0; k < 3; ++k) m.pose[k] += noise.position * unit(*rng);
    for (int k = 3; k < 6; ++k) m.pose[k] += noise.angle_deg * unit(*rng);
    for (int i = 0; i < kNumLegs; ++i) m.legs[i] += noise.leg * unit(*rng);
    measurements.push_back(m);
  }
  return measurements;
}

StatusOr<SimulationResult> Simulate(const Robot& nominal, const std::vector<SimulationPoseSet>& sets,
                                    const SimulationOptions& options, const JobHooks& hooks) {
  if (Status s = options.Check(); !s.ok()) return s;
  if (Status s = CheckSets(sets); !s.ok()) return s;
  StudySizes sizes(1);
  for (const SimulationPoseSet& set : sets) sizes[0].push_back(set.Size());
  SimulationResult result;
  const Robot true_robot = PerturbedRobot(nominal, options.perturb, options.seed);
  result.true_parameters = ParametersOf(true_robot);
  result.before = BeforeCalibration(nominal, true_robot);
  StatusOr<std::vector<std::vector<SetError>>> errors = RunStudy(nominal, true_robot, sets, sizes, options, hooks);
  if (!errors.ok()) return errors.status();
  result.sets = std::move((*errors)[0]);
  return result;
}

StatusOr<SweepResult> SimulateSweep(const Robot& nominal, const std::vector<SimulationPoseSet>& sets, int min_poses,
                                    int max_poses, const SimulationOptions& options, const JobHooks& hooks) {
  if (Status s = options.Check(); !s.ok()) return s;
  if (Status s = CheckSets(sets); !s.ok()) return s;
  if (!IsSweepRange(min_poses, max_poses)) {
    return Status::BadOption("sweep", std::to_string(min_poses) + ":" + std::to_string(max_poses) +
                                          " is not MIN:MAX with " + SweepRangeRule());
  }
  StudySizes sizes;
  for (int n = min_poses; n <= max_poses; ++n) {
    std::vector<int> point;
    for (const SimulationPoseSet& set : sets) point.push_back(set.random || n <= set.Size() ? n : 0);
    sizes.push_back(point);
  }
  SweepResult result;
  const Robot true_robot = PerturbedRobot(nominal, options.perturb, options.seed);
  result.before = BeforeCalibration(nominal, true_robot);
  StatusOr<std::vector<std::vector<SetError>>> errors = RunStudy(nominal, true_robot, sets, sizes, options, hooks);
  if (!errors.ok()) return errors.status();
  for (size_t p = 0; p < sizes.size(); ++p) result.points.push_back({min_poses + static_cast<int>(p), (*errors)[p]});
  return result;
}

}  // namespace hexcal

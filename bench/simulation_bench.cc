// The section 7 study at the paper's size: 100 runs of four pose sets on the
// INRIA robot (random 18, boundary 44, and two 18-pose IOOPS plans from the
// boundary candidates: O1, and O1 with O4 as the secondary criterion, the
// paper's Υ_s1 and Υ_s4). Each run simulates noisy measurements of every set
// and calibrates 4 x 6 legs. The pose sets are made once, outside the timing.
// Figures: docs/performance.md.
//   build/bench/hexcal_bench_simulation
#include <benchmark/benchmark.h>

#include "bench/bench_support.h"
#include "core/candidates.h"
#include "core/ioops.h"
#include "core/simulation.h"

namespace hexcal {
namespace {

using bench::Inria;

std::vector<Vector6d> Candidates(CandidateKind kind, int count) {
  CandidateOptions options;
  options.kind = kind;
  options.count = count;
  return GenerateCandidates(Inria(), options)->poses;
}

std::vector<Vector6d> Plan(const std::vector<Vector6d>& candidates, std::optional<Criterion> secondary) {
  PlannerOptions options;
  options.secondary = secondary;
  const PlanningModel model{Inria(), std::nullopt, std::nullopt};
  return PlanPoses(model, candidates, Candidates(CandidateKind::kRandom, options.num_poses), options)->poses;
}

const std::vector<SimulationPoseSet>& FourSets() {
  static const std::vector<SimulationPoseSet> sets = [] {
    const std::vector<Vector6d> boundary = Candidates(CandidateKind::kBoundary, 0);
    return std::vector<SimulationPoseSet>{RandomPoseSet(18), FixedPoseSet("boundary", boundary),
                                          FixedPoseSet("plan O1", Plan(boundary, std::nullopt)),
                                          FixedPoseSet("plan O1/O4", Plan(boundary, Criterion::kO4))};
  }();
  return sets;
}

// Argument: threads (0 = every core).
void BM_Simulation100Runs4Sets(benchmark::State& state) {
  const std::vector<SimulationPoseSet>& sets = FourSets();
  SimulationOptions options;
  options.runs = 100;
  options.num_threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    StatusOr<SimulationResult> result = Simulate(Inria(), sets, options);
    if (!result.ok()) state.SkipWithError(result.status().message().c_str());
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations() * options.runs * sets.size());  // calibrations of 6 legs
}
BENCHMARK(BM_Simulation100Runs4Sets)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// One calibration of 18 noisy measurements, with and without the uncertainty report.
void BM_Calibrate18Poses(benchmark::State& state) {
  const Robot truth = PerturbedRobot(Inria(), 0.5, 1);
  std::mt19937_64 rng(1);
  const std::vector<Measurement> measurements =
      SimulateMeasurements(truth, Candidates(CandidateKind::kUniform, 18), NoiseModel{}, &rng);
  CalibrationOptions options;
  options.num_threads = 1;
  options.compute_uncertainty = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(Calibrate(Inria(), measurements, options));
}
BENCHMARK(BM_Calibrate18Poses)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace hexcal

BENCHMARK_MAIN();

// Planner benchmarks (issue: incremental vs naive AddFind, whole plan).
//   build/bench/hexcal_bench_planner
// AddFind scores W candidates against an 18-pose plan. "Incremental" uses
// DesignState::ScoreAdditions (determinant lemma with the Cholesky factor for
// O1; secular equation for O4); "Naive" rebuilds and decomposes the six 7x7
// blocks for every candidate. Both single-threaded, same candidates, same run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "bench/bench_support.h"
#include "core/candidates.h"
#include "core/ioops.h"

namespace hexcal {
namespace {

const PlanningModel& Model() {
  static const PlanningModel model{bench::Inria(), std::nullopt, std::nullopt};
  return model;
}

// 10^5 feasible random INRIA poses, generated once (about 15 s).
const std::vector<Vector6d>& Candidates() {
  static const std::vector<Vector6d> poses = [] {
    CandidateOptions options;
    options.count = 100000;
    options.seed = 11;
    return GenerateCandidates(Model().robot, options)->poses;
  }();
  return poses;
}

std::vector<Vector6d> Plan18() {
  return std::vector<Vector6d>(Candidates().begin(), Candidates().begin() + 18);
}

DesignState PlanState() {
  std::vector<PoseRows> rows;
  for (const Vector6d& v : Plan18()) rows.push_back(Model().Rows(v));
  return DesignState::FromRows(rows);
}

CandidateRows RowsOf(int count) {
  CandidateRows rows;
  rows.Resize(count);
  for (int j = 0; j < count; ++j) rows.Set(j, Model().Rows(Candidates()[j]));
  return rows;
}

void AddFindIncremental(benchmark::State& state, Criterion criterion) {
  const int count = static_cast<int>(state.range(0));
  const CandidateRows rows = RowsOf(count);
  const DesignState design = PlanState();
  std::vector<double> scores(count);
  for (auto _ : state) {
    design.ScoreAdditions(criterion, rows, 0, count, scores.data());
    benchmark::DoNotOptimize(scores.data());
  }
  state.SetItemsProcessed(state.iterations() * count);
}

void AddFindNaive(benchmark::State& state, Criterion criterion) {
  const int count = static_cast<int>(state.range(0));
  const CandidateRows rows = RowsOf(count);
  const DesignState design = PlanState();
  for (auto _ : state) {
    double best = 0;
    for (int j = 0; j < count; ++j) best = std::max(best, design.ValueAfterAdding(criterion, rows.Rows(j)));
    benchmark::DoNotOptimize(best);
  }
  state.SetItemsProcessed(state.iterations() * count);
}

void BM_AddFindIncrementalO1(benchmark::State& s) { AddFindIncremental(s, Criterion::kO1); }
void BM_AddFindNaiveO1(benchmark::State& s) { AddFindNaive(s, Criterion::kO1); }
void BM_AddFindIncrementalO4(benchmark::State& s) { AddFindIncremental(s, Criterion::kO4); }
void BM_AddFindNaiveO4(benchmark::State& s) { AddFindNaive(s, Criterion::kO4); }
BENCHMARK(BM_AddFindIncrementalO1)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AddFindNaiveO1)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AddFindIncrementalO4)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AddFindNaiveO4)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// A whole plan: N = 18, W = 10^5, Tabu 4, 200 iterations, O1, one thread.
void BM_WholePlanOneCore(benchmark::State& state) {
  PlannerOptions options;
  options.tabu = 4;
  options.iterations = 200;
  options.threads = 1;
  const std::vector<Vector6d>& candidates = Candidates();  // generated outside the timing
  const std::vector<Vector6d> initial = Plan18();
  for (auto _ : state) benchmark::DoNotOptimize(PlanPoses(Model(), candidates, initial, options));
}
BENCHMARK(BM_WholePlanOneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

double PlanSeconds(const std::vector<Vector6d>& candidates, const PlannerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(PlanPoses(Model(), candidates, Plan18(), options));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Section 6.2's O1 with O4 secondary against O1 alone, same 10^4 candidates,
// Tabu 4, 200 iterations, both cores, alternated in the same run: the ratio
// of the medians (docs/performance.md; goal <= 3).
void BM_SecondaryO4OverO1Alone(benchmark::State& state) {
  const std::vector<Vector6d> candidates(Candidates().begin(), Candidates().begin() + 10000);
  PlannerOptions o1;
  o1.tabu = 4;
  o1.iterations = 200;
  PlannerOptions o4 = o1;
  o4.secondary = Criterion::kO4;
  std::vector<double> o1_seconds, o4_seconds;
  for (auto _ : state) {
    o1_seconds.push_back(PlanSeconds(candidates, o1));
    o4_seconds.push_back(PlanSeconds(candidates, o4));
  }
  state.counters["O1_s"] = Median(o1_seconds);
  state.counters["O1+O4_s"] = Median(o4_seconds);
  state.counters["ratio"] = Median(o4_seconds) / Median(o1_seconds);
}
BENCHMARK(BM_SecondaryO4OverO1Alone)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace hexcal

BENCHMARK_MAIN();

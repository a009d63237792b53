// Benchmarks of the kinematics core: IK, Jacobian rows, observability indices,
// local FK and FK with every assembly mode. Figures: docs/performance.md.
//   build/bench/hexcal_bench_kinematics
#include <benchmark/benchmark.h>

#include <random>

#include "bench/bench_support.h"
#include "core/fk_homotopy.h"
#include "core/forward_kinematics.h"
#include "core/identification.h"
#include "core/observability.h"

namespace hexcal {
namespace {

using bench::Inria;

std::vector<Pose> RandomPoses(int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pose> poses;
  for (int k = 0; k < count; ++k) {
    Vector6d v;
    v << 2 * u(rng), 2 * u(rng), 53.5 + u(rng), 5 * u(rng), 5 * u(rng), 5 * u(rng);
    poses.push_back(Inria().PoseFromVector(v));
  }
  return poses;
}

void BM_InverseKinematics(benchmark::State& state) {
  const std::vector<Pose> poses = RandomPoses(1024, 1);
  size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(InverseKinematics(Inria(), poses[k++ % poses.size()]));
}
BENCHMARK(BM_InverseKinematics);

void BM_JacobianRows(benchmark::State& state) {  // the six rows of one pose
  const std::vector<Pose> poses = RandomPoses(1024, 2);
  size_t k = 0;
  for (auto _ : state) {
    const Pose& pose = poses[k++ % poses.size()];
    for (int i = 0; i < kNumLegs; ++i) benchmark::DoNotOptimize(NominalJacobianRow(Inria().legs[i], pose));
  }
}
BENCHMARK(BM_JacobianRows);

void BM_IndicesOf18Poses(benchmark::State& state) {
  const std::vector<Pose> poses = RandomPoses(18, 3);
  for (auto _ : state) benchmark::DoNotOptimize(ComputeIndices(Inria(), poses));
}
BENCHMARK(BM_IndicesOf18Poses);

void BM_ForwardKinematicsLocal(benchmark::State& state) {
  const std::vector<Pose> poses = RandomPoses(256, 4);
  size_t k = 0;
  for (auto _ : state) {
    const Pose& truth = poses[k++ % poses.size()];
    Pose start = truth;
    start.position.z() += 0.5;
    benchmark::DoNotOptimize(ForwardKinematicsLocal(Inria(), InverseKinematics(Inria(), truth), start));
  }
}
BENCHMARK(BM_ForwardKinematicsLocal);

void BM_ForwardKinematicsAllModes(benchmark::State& state) {
  GenericStartSystem();  // one-time cost, measured separately below
  const std::vector<Pose> poses = RandomPoses(64, 5);
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ForwardKinematicsAll(Inria(), InverseKinematics(Inria(), poses[k++ % poses.size()])));
  }
}
BENCHMARK(BM_ForwardKinematicsAllModes)->Unit(benchmark::kMillisecond);

void BM_GenericStartSystem(benchmark::State& state) {  // the one-time 128-path solve
  for (auto _ : state) benchmark::DoNotOptimize(SolveGenericInstance(20050601));
}
BENCHMARK(BM_GenericStartSystem)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace hexcal

BENCHMARK_MAIN();

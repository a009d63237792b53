// ParallelFor: runs body(0) .. body(count - 1) on up to `threads` threads
// (0 = every core), each index exactly once, in no particular order. Results
// must go to per-index slots so that they do not depend on the thread count.
//
//   std::vector<double> out(n);
//   ParallelFor(n, 0, [&](int k) { out[k] = Work(k); });
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace hexcal {

inline int ResolveThreadCount(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

template <typename Body>
void ParallelFor(int count, int threads, Body&& body) {
  const int workers = std::min(ResolveThreadCount(threads), count);
  if (workers <= 1) {
    for (int k = 0; k < count; ++k) body(k);
    return;
  }
  std::atomic<int> next{0};
  auto work = [&] {
    for (int k = next++; k < count; k = next++) body(k);
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
}

}  // namespace hexcal

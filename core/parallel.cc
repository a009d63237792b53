#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

namespace hexcal {

int ResolveThreadCount(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

int ParallelWorkers(int count, int threads) { return std::max(1, std::min(ResolveThreadCount(threads), count)); }

bool ParallelFor(int count, int threads, const std::function<void(int index, int worker)>& body,
                 const JobHooks& hooks) {
  std::atomic<int> next{0};
  std::atomic<bool> cancelled{false};
  std::mutex progress_mutex;
  int done = 0;
  auto work = [&](int worker) {
    while (true) {
      const int index = next++;
      if (index >= count) return;
      if (hooks.Cancelled()) {
        cancelled = true;
        return;
      }
      body(index, worker);
      if (hooks.progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        hooks.progress(++done, count);
      }
    }
  };
  const int workers = ParallelWorkers(count, threads);
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& thread : pool) thread.join();
  return !cancelled;
}

void ParallelForBlocks(int count, int block, int threads, const std::function<void(int begin, int end)>& body) {
  const int blocks = (count + block - 1) / block;
  ParallelFor(blocks, threads, [&](int k, int) { body(k * block, std::min(count, (k + 1) * block)); });
}

}  // namespace hexcal

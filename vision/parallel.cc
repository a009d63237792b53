#include "vision/parallel.h"

#include <algorithm>
#include <mutex>
#include <thread>
#include <vector>

namespace hexcal {

bool ParallelFor(int count, int threads, const std::function<void(int index, int worker)>& body,
                 const std::function<void(int done, int total)>& progress, const std::atomic<bool>* cancel) {
  std::atomic<int> next{0};
  std::atomic<bool> cancelled{false};
  std::mutex progress_mutex;
  int done = 0;
  auto work = [&](int worker) {
    while (true) {
      if (cancel && cancel->load()) {
        cancelled = true;
        return;
      }
      const int index = next++;
      if (index >= count) return;
      body(index, worker);
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(++done, count);
      }
    }
  };
  const int workers = std::max(1, std::min(threads, count));
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& thread : pool) thread.join();
  return !cancelled;
}

}  // namespace hexcal

#include "core/parallel.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace hexcal {

namespace {

// work(0) on the calling thread, holding back what it throws: other threads
// run `work` too, and the caller rethrows only once they are done with it.
std::exception_ptr RunCallersShare(const std::function<void(int)>& work) {
  try {
    work(0);
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

// Threads kept between calls: a search calls ParallelFor hundreds of times a
// second on blocks of a few milliseconds, and a thread started per call came
// up after the calling thread had taken most of the blocks. One job at a
// time, at most one helper per core beyond the caller's; a call made while
// the pool is busy (from another thread, or nested inside a job), one that
// wants more threads than that, and one in a forked child (which has none of
// the pool's threads) start their own threads instead, as before. Never
// destroyed, so that no exit-time destructor joins threads still waiting.
class WorkerPool {
 public:
  static WorkerPool& Instance() {
    static WorkerPool* pool = new WorkerPool;
    return *pool;
  }

  // work(1) .. work(helpers) on pool threads and work(0) on the caller's,
  // returning when all are done; false, having run nothing, when busy.
  bool TryRun(int helpers, const std::function<void(int)>& work) {
    if (::getpid() != owner_ || helpers > max_helpers_) return false;
    bool idle = false;
    if (!busy_.compare_exchange_strong(idle, true)) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      try {
        while (static_cast<int>(threads_.size()) < helpers) {
          const int worker = static_cast<int>(threads_.size()) + 1;
          threads_.emplace_back([this, worker] { Serve(worker); });
        }
      } catch (const std::system_error&) {  // no thread to be had: the caller's own attempt reports it
        busy_ = false;
        return false;
      }
      job_ = &work;
      helpers_ = helpers;
      pending_ = helpers;
      ++generation_;
    }
    started_.notify_all();
    const std::exception_ptr thrown = RunCallersShare(work);
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, [&] { return pending_ == 0; });
    job_ = nullptr;
    busy_ = false;
    if (thrown) std::rethrow_exception(thrown);
    return true;
  }

 private:
  void Serve(int worker) {
    long seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      started_.wait(lock, [&] { return generation_ != seen; });
      seen = generation_;
      if (worker > helpers_) continue;
      const std::function<void(int)>* job = job_;
      lock.unlock();
      (*job)(worker);
      lock.lock();
      if (--pending_ == 0) finished_.notify_one();
    }
  }

  const pid_t owner_ = ::getpid();  // the process whose threads these are
  const int max_helpers_ = ResolveThreadCount(0) - 1;
  std::atomic<bool> busy_{false};  // a caller's job is running (a flag, not a mutex: nested calls test it)
  std::mutex mutex_;  // guards what follows
  std::condition_variable started_, finished_;
  std::vector<std::thread> threads_;  // threads_[k] serves worker k + 1
  const std::function<void(int)>* job_ = nullptr;
  int helpers_ = 0, pending_ = 0;
  long generation_ = 0;
};

}  // namespace

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
  if (workers == 1) {
    work(0);
  } else if (!WorkerPool::Instance().TryRun(workers - 1, work)) {
    std::vector<std::thread> own;
    for (int w = 1; w < workers; ++w) own.emplace_back(work, w);
    const std::exception_ptr thrown = RunCallersShare(work);
    for (std::thread& thread : own) thread.join();
    if (thrown) std::rethrow_exception(thrown);
  }
  return !cancelled;
}

void ParallelForBlocks(int count, int block, int threads, const std::function<void(int begin, int end)>& body) {
  const int blocks = (count + block - 1) / block;
  ParallelFor(blocks, threads, [&](int k, int) { body(k * block, std::min(count, (k + 1) * block)); });
}

}  // namespace hexcal

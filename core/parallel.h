// ParallelFor, the one thread pool of core and vision: body(index, worker) for
// index 0 .. count - 1, each index exactly once, in no particular order, on
// ParallelWorkers(count, threads) threads (threads = 0: every core). `worker`
// (0 .. workers - 1) names the calling thread, for per-thread state such as
// one tag detector each. Results must go to per-index slots so that they do
// not depend on the thread count or on the order in which items finish. The
// threads are kept between calls; a call made while they serve another one
// (from another thread, or nested in a body) starts threads of its own.
// Bodies should not throw: an exception thrown on the calling thread comes out
// of ParallelFor once the other threads have run the remaining items; one
// thrown on another thread ends the process.
//
// hooks.Progress(done, count) is called after each item, serialised (never
// two at once), from whichever worker finished it. hooks.Cancelled() is polled
// before each item; once it is raised the remaining items are skipped and
// ParallelFor returns false.
//
//   std::vector<double> out(n);
//   ParallelFor(n, 0, [&](int k, int /*worker*/) { out[k] = Work(k); });
#pragma once

#include <functional>

#include "core/job_hooks.h"

namespace hexcal {

// `threads` itself when positive, else the number of cores (at least 1).
int ResolveThreadCount(int threads);

// The threads ParallelFor(count, threads, ...) runs on: at least 1, at most count.
int ParallelWorkers(int count, int threads);

// False when hooks.cancel was raised before every item had started (those were skipped).
bool ParallelFor(int count, int threads, const std::function<void(int index, int worker)>& body,
                 const JobHooks& hooks = {});

// body(begin, end) for the blocks [0, block), [block, 2 block), ... of
// [0, count), spread over the threads as ParallelFor's items: for vectorised
// work on many small items (scoring candidates). The block bounds depend on
// count and block only, never on the thread count.
void ParallelForBlocks(int count, int block, int threads, const std::function<void(int begin, int end)>& body);

}  // namespace hexcal

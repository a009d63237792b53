// A fixed pool of worker threads over the indices 0 .. count-1, for the image
// batches (detection, measurement, rendering). Worker w handles the indices it
// takes from a shared counter, so a result must be stored by index, never by
// completion order; `progress` is called after each item, serialised by a
// mutex, from whichever worker finished it.
//
//   bool finished = ParallelFor(files.size(), 2, [&](int index, int worker) { ... }, progress, &cancel);
#pragma once

#include <atomic>
#include <functional>

namespace hexcal {

// Returns false when `cancel` was raised (the remaining items are skipped).
bool ParallelFor(int count, int threads, const std::function<void(int index, int worker)>& body,
                 const std::function<void(int done, int total)>& progress = nullptr,
                 const std::atomic<bool>* cancel = nullptr);

}  // namespace hexcal

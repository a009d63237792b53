// JobHooks: how the caller of a long job (planning, calibration, simulation,
// image batches) watches and stops it. One type for core and vision, so a
// front end hands the same hooks to every step: the CLI a progress bar, the
// GUI a queued signal and its Cancel button's flag.
//
// A job polls Cancelled() between units of work and then returns
// Status::Cancelled (core/status.h); it calls Progress(done, total) as units
// finish, one call at a time, possibly from a worker thread.
//
//   std::atomic<bool> cancel{false};
//   JobHooks hooks{[&](int done, int total) { bar.Update(done, total); }, &cancel};
//   StatusOr<CalibrationResult> result = Calibrate(nominal, measurements, options, hooks);
#pragma once

#include <atomic>
#include <functional>

namespace hexcal {

struct JobHooks {
  std::function<void(int done, int total)> progress;  // may be empty
  const std::atomic<bool>* cancel = nullptr;          // raised by the caller to stop; may be null

  bool Cancelled() const { return cancel != nullptr && cancel->load(); }
  void Progress(int done, int total) const {
    if (progress) progress(done, total);
  }
};

}  // namespace hexcal

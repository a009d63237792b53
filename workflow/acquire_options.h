// The options of the Acquire step (docs/acquisition.md): how long to wait
// after each move and for each frame, and which poses to hold out — each
// described once in AcquireOptionSpecs() (core/option_spec.h). That table
// makes the `hexcal acquire` flags and the table in docs/cli.md, and Check()
// checks the struct against it.
//
//   AcquireOptions options;  // the controller's settle time, 5 s for a frame, none held out
//   Status s = ApplyOptionEntries(AcquireOptionSpecs(), {{"settle", "0.3"}}, &options, "acquire");
#pragma once

#include <optional>

#include "core/option_spec.h"
#include "core/session_lock.h"
#include "core/status.h"

namespace hexcal::workflow {

struct AcquireOptions {
  // Waited after each move ends, before the frame, seconds; unset: the
  // controller's own (Controller::DefaultSettleSeconds: 0 for sim, 0.5 for
  // LinuxCNC, whose camera needs it or shows the previous pose).
  std::optional<double> settle_seconds;
  int grab_timeout_ms = 5000;  // a frame later than this is a failed pose, milliseconds
  // Every Nth pose of the plan (rows N-1, 2N-1, ...) is recorded with
  // holdout = 1, kept out of the calibration to validate it; 0 = none.
  int holdout_every = 0;
  LockWait wait = LockWait::kNo;  // another writer holds the session: stop, or wait

  // The ranges of AcquireOptionSpecs(), then the rule no range can say
  // (holdout_every 1 would hold out every pose); an error names the option
  // by its key (Status::option()).
  Status Check() const;
};

// settle, grab_timeout, holdout_every (`wait` says how to run, not what to record).
const OptionTable<AcquireOptions>& AcquireOptionSpecs();

}  // namespace hexcal::workflow

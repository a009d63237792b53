#include "workflow/acquire_options.h"

#include <string>

namespace hexcal::workflow {

const OptionTable<AcquireOptions>& AcquireOptionSpecs() {
  static const OptionTable<AcquireOptions> table = [] {
    using Options = AcquireOptions;
    return OptionTable<Options>{
        OptionalNumberOption<Options>("settle", "Settle time", "s", 0, 600,
                                      "waited after each move ends, before the frame",
                                      "the controller's (sim 0, LinuxCNC 0.5)",
                                      [](Options& o) -> std::optional<double>& { return o.settle_seconds; }),
        NumberOption<Options>("grab_timeout", "Frame time-out", OptionType::kInteger, "ms", 1, 600000,
                              "a frame later than this fails its pose, and the run goes on",
                              [](Options& o) -> int& { return o.grab_timeout_ms; }),
        NumberOption<Options>("holdout_every", "Hold out every", OptionType::kInteger, "poses", 0, 1000000,
                              "hold out every Nth pose (rows N-1, 2N-1, ...) to validate the calibration; 0 = none, "
                              "else at least 2",
                              [](Options& o) -> int& { return o.holdout_every; })};
  }();
  return table;
}

Status AcquireOptions::Check() const {
  if (Status s = CheckOptionRanges(AcquireOptionSpecs(), *this); !s.ok()) return s;
  if (holdout_every == 1)
    return Status::BadOption("holdout_every", "must be 0 (none) or at least 2, got 1 (every pose held out)");
  return Status::Ok();
}

}  // namespace hexcal::workflow

// The session steps behind `hexcal calibrate --session DIR` (docs/session.md):
// measure the images not yet in measurements.csv, register the camera and
// target frames with the nominal robot, calibrate on the rows not held out,
// validate on the held-out rows, write results/. Lives in app/ because it
// measures images (vision); core/session.h holds the folder itself.
#pragma once

#include <ostream>
#include <string>

#include "core/job_hooks.h"

namespace hexcal::cli {

// A name in session.yaml: a file relative to the session folder when one
// exists there, otherwise as given (a preset name or a path).
std::string ResolveSessionFile(const std::string& dir, const std::string& name);

// Exit code as every command's: 0, kExitFailure or kExitBadInput; a cancelled
// run returns kExitFailure with "cancelled" and writes nothing new to results/.
// `hooks` are for a caller with its own progress display and a Cancel button
// (the GUI): progress is (done, total) of the current stage, images measured
// then legs calibrated; cancel stops at the next image or solver iteration.
int RunSessionCalibrate(const std::string& dir, bool json, std::ostream& out, std::ostream& err,
                        const JobHooks& hooks = {});

}  // namespace hexcal::cli

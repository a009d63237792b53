// The session steps behind `hexcal calibrate --session DIR` (docs/session.md):
// measure the images not yet in measurements.csv, register the camera and
// target frames with the nominal robot, calibrate on the rows not held out,
// validate on the held-out rows, write results/. Lives in app/ because it
// measures images (vision); core/session.h holds the folder itself.
#pragma once

#include <ostream>
#include <string>

namespace hexcal::cli {

// Exit code as every command's: 0, kExitFailure or kExitBadInput.
int RunSessionCalibrate(const std::string& dir, bool json, std::ostream& out, std::ostream& err);

}  // namespace hexcal::cli

// The lines `hexcal calibrate --session` prints (docs/session.md,
// docs/calibration.md): counts, the registration's closure and the calibrated
// one, held-out validation, the calibration from pixels, the camera-frame
// residuals, one warning per outlier reading, the images left out and the
// worst image's closure, the files written.
//
//   std::cout << FormatCalibrationSummary(*report);
#pragma once

#include <string>

#include "session/calibration_report.h"

namespace hexcal::workflow {

std::string FormatCalibrationSummary(const CalibrationReport& report);

}  // namespace hexcal::workflow

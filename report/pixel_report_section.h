// The "Calibration" section of the HTML report (session_report.h): which
// method gave the parameters, and for the calibration from pixels its fit,
// the camera and target quantities it estimated with σ, what it could hardly
// separate, and the two-stage figures it replaced (docs/calibration.md,
// "Calibration from pixels"); for a points session, the calibration from
// points with its reflectors ("Calibration from points").
//
//   html += CalibrationMethodSection(report);
#pragma once

#include <string>

#include "session/calibration_report.h"

namespace hexcal::workflow {

std::string CalibrationMethodSection(const CalibrationReport& report);

}  // namespace hexcal::workflow

// The files of a session's results/ folder, named once (issue 37): what
// `calibrate --session` publishes as one unit (session_results.h checks them
// against manifest.json) and what the report, the verdict and the GUI read.
// A message or a page that names one to the operator says ResultsName(...).
//
//   StatusOr<Robot> calibrated = LoadRobot(ResultsFile("run1", kCalibratedRobot));  // run1/results/calibrated.yaml
//   advice = "make " + ResultsName(kFittedReflectors) + " the session's reflector file";
#pragma once

#include <string>

namespace hexcal::workflow {

// Every calibration writes these.
inline constexpr const char* kCalibratedRobot = "calibrated.yaml";                // the robot, with what made it
inline constexpr const char* kUsedMeasurements = "calibration_measurements.csv";  // the rows it was fitted to
inline constexpr const char* kReportJson = "report.json";                         // calibration_report.h
inline constexpr const char* kResultsManifest = "manifest.json";                  // session_results.h
// The calibration from pixels: the estimated intrinsics, every corner's residual.
inline constexpr const char* kFittedCamera = "camera.yaml";
inline constexpr const char* kCornerResiduals = "corner_residuals.csv";
// The calibration from points: the fitted reflectors, every point's residual.
inline constexpr const char* kFittedReflectors = "reflectors.csv";
inline constexpr const char* kPointResiduals = "point_residuals.csv";
// `hexcal report`'s page, written beside them later (not in the manifest).
inline constexpr const char* kHtmlReport = "report.html";

// DIR/results/NAME.
std::string ResultsFile(const std::string& session_dir, const char* name);
// "results/NAME", as a message names the file inside the session.
std::string ResultsName(const char* name);

}  // namespace hexcal::workflow

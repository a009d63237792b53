// The checks behind MakeVerdict (calibration_verdict.h), one finding each;
// thresholds are in verdict_findings.h, their reasons in docs/calibration.md,
// "Verdict".
//
//   Verdict verdict;
//   verdict.Add(CheckHeldOut(report));  // report: results/report.json's CalibrationReport
//   if (std::optional<Finding> scale = CheckCameraScale(report)) verdict.Add(*scale);
#pragma once

#include <optional>
#include <string>

#include "core/validation.h"
#include "report/expected_error.h"
#include "report/verdict_findings.h"
#include "session/calibration_report.h"

namespace hexcal::workflow {

// FK errors against the noise prediction; `worst_image` names where to add
// poses (an image, or a points session's pose: `instrument` says which, and
// what measured it).
Finding CheckFkErrors(const PoseErrorStats& after, const ExpectedPoseError& expected, const std::string& unit,
                      const std::string& worst_image, Instrument instrument = Instrument::kCamera);
Finding CheckHeldOut(const CalibrationReport& report);
Finding CheckClosure(const CalibrationReport& report);  // needs report.noise
Finding CheckResiduals(const CalibrationReport& report);
Finding CheckParameterSigmas(const CalibrationReport& report);  // needs report.noise
Finding CheckParameterChanges(const CalibrationReport& report);
Finding CheckTruth(const VerdictTruth& truth);
std::optional<Finding> CheckConditioning(const CalibrationReport& report);  // none without condition numbers
Finding CheckPoses(const CalibrationReport& report);
Finding CheckUnusableImages(const CalibrationReport& report);
Finding CheckOutliers(const CalibrationReport& report);
// None without a calibration from pixels that estimated fx, fy or the target's scale.
std::optional<Finding> CheckCameraScale(const CalibrationReport& report);
// None without a calibration from points that estimated reflectors given by a file.
std::optional<Finding> CheckReflectorScale(const CalibrationReport& report);
// The estimate among fx, fy and target_scale that moved most from its file value, relatively.
std::optional<PixelEstimateSummary> LargestScaleChange(const CalibrationReport& report);
// "the camera file's fx is 5 % off (the fit's 903 ± 0.04 against the file's 948)".
std::string ScaleChangeText(const PixelEstimateSummary& change);

// Level of a figure where smaller is better / larger is better.
VerdictLevel LevelAtMost(double value, double good, double acceptable);
VerdictLevel LevelAtLeast(double value, double good, double acceptable);
// A number with 3 significant digits ("0.00412", "1.3e+04").
std::string Figure(double value);
// "1 image", "3 images".
std::string Plural(int count, const std::string& noun);

}  // namespace hexcal::workflow

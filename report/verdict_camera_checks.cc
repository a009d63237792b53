// The camera finding of the verdict (calibration_verdict.h): how far the
// calibration from pixels moved the camera file's focal lengths and the
// target's scale; and a points session's counterpart, how far the
// calibration from points moved the reflectors' size from the file's. The fit corrects them, but the registration and the
// two-stage start used the file's: a focal or scale error is named as such,
// not blamed on the robot file.
#include <cmath>

#include "report/verdict_checks.h"
#include "session/results_files.h"

namespace hexcal::workflow {

std::optional<PixelEstimateSummary> LargestScaleChange(const CalibrationReport& report) {
  if (!report.from_pixels) return std::nullopt;
  std::optional<PixelEstimateSummary> largest;
  auto relative = [](const PixelEstimateSummary& e) { return std::abs(e.estimate / e.file_value - 1); };
  for (const PixelEstimateSummary& e : report.from_pixels->estimated) {
    const bool scale = e.name == "fx" || e.name == "fy" || e.name == "target_scale";
    if (scale && e.file_value != 0 && (!largest || relative(e) > relative(*largest))) largest = e;
  }
  return largest;
}

std::string ScaleChangeText(const PixelEstimateSummary& change) {
  const std::string what = change.name == "target_scale" ? "the target's scale" : "the camera file's " + change.name;
  return what + " is " + Figure(100 * (change.file_value / change.estimate - 1)) + " % off (the fit's " +
         Figure(change.estimate) + " ± " + Figure(change.sigma) + " against the file's " + Figure(change.file_value) +
         ")";
}

std::optional<Finding> CheckCameraScale(const CalibrationReport& report) {
  const std::optional<PixelEstimateSummary> largest = LargestScaleChange(report);
  if (!largest) return std::nullopt;
  const double change = std::abs(largest->estimate / largest->file_value - 1);
  Finding finding{"camera (scale)",
                  LevelAtMost(change, kScaleChangeGood, kScaleChangeAcceptable),
                  "largest change " + Figure(100 * change) + " % (" + largest->name + " " +
                      Figure(largest->file_value) + " -> " + Figure(largest->estimate) + " ± " +
                      Figure(largest->sigma) + ")",
                  "good ≤ " + Figure(100 * kScaleChangeGood) + " %, acceptable ≤ " +
                      Figure(100 * kScaleChangeAcceptable) + " % of the file's",
                  "the camera file's focal lengths and the target's tag size agree with the images and legs.",
                  ""};
  if (finding.level == VerdictLevel::kGood) return finding;
  finding.meaning = ScaleChangeText(*largest) +
                    ": the fit corrected it, but the registered frames and the parameters' changes carry it.";
  finding.advice = largest->name == "target_scale"
                       ? "check the target file's tag size against the printed board, then calibrate again"
                       : "recalibrate the camera (hexcal intrinsics) or make " + ResultsName(kFittedCamera) +
                             " the session's camera, then calibrate again";
  return finding;
}

std::optional<Finding> CheckReflectorScale(const CalibrationReport& report) {
  if (!report.from_points || !report.from_points->reflectors_estimated || !report.from_points->reflectors_from_file)
    return std::nullopt;
  const PointFitSummary& fit = *report.from_points;
  const double change = std::abs(fit.reflector_scale - 1);
  Finding finding{"reflectors (scale)",
                  LevelAtMost(change, kScaleChangeGood, kScaleChangeAcceptable),
                  "the fitted reflectors' size is " + Figure(fit.reflector_scale) + " ± " +
                      Figure(fit.reflector_scale_sigma) + " of the reflector file's (" +
                      Figure(100 * change) + " % change)",
                  "good ≤ " + Figure(100 * kScaleChangeGood) + " %, acceptable ≤ " +
                      Figure(100 * kScaleChangeAcceptable) + " % of the file's",
                  "the reflector file and the tracker agree on the reflectors' distances.",
                  ""};
  if (finding.level == VerdictLevel::kGood) return finding;
  finding.meaning = "the reflector file's distances are " + Figure(100 * (1 / fit.reflector_scale - 1)) +
                    " % off what the tracker measured: the fit corrected them, but the registered frames and the "
                    "two-stage start carry it.";
  finding.advice = "check the reflector file's unit and the tracker's scale (temperature compensation), or make " +
                   ResultsName(kFittedReflectors) + " the session's reflector file, then calibrate again";
  return finding;
}

}  // namespace hexcal::workflow

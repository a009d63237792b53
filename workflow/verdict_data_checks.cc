// The data findings of the verdict (calibration_verdict.h): how many poses,
// unusable images, outlier readings.
#include <algorithm>
#include <cmath>

#include "core/outlier_screening.h"
#include "workflow/verdict_checks.h"

namespace hexcal::workflow {

Finding CheckPoses(const CalibrationReport& report) {
  const int calibration = report.calibration_images, held_out = report.held_out_images;
  VerdictLevel level = calibration >= kCalibrationImagesGood ? VerdictLevel::kGood
                       : calibration >= kMinRowsToScreen     ? VerdictLevel::kAcceptable
                                                             : VerdictLevel::kPoor;
  if (held_out > 0 && held_out < kHeldOutImagesGood) level = std::max(level, VerdictLevel::kAcceptable);
  Finding finding{"poses",
                  level,
                  Plural(calibration, "calibration image") + ", " + std::to_string(held_out) + " held out",
                  "good ≥ " + std::to_string(kCalibrationImagesGood) +
                      " calibration images, 3 per leg parameter, and ≥ " + std::to_string(kHeldOutImagesGood) +
                      " held out; poor < " + std::to_string(kMinRowsToScreen),
                  "enough poses to fit each leg's 7 parameters with redundancy to spare.",
                  ""};
  if (calibration < kCalibrationImagesGood) {
    finding.meaning = "few poses per leg parameter: σ and the outlier screening rest on little redundancy.";
    finding.advice = "measure at least " + std::to_string(kCalibrationImagesGood - calibration) +
                     " more planned poses (hexcal plan)";
  } else if (level != VerdictLevel::kGood) {
    finding.meaning = "too few held-out poses to judge the calibration on new poses reliably.";
    finding.advice = "hold out at least " + std::to_string(kHeldOutImagesGood) + " images (holdout = 1 in legs.csv)";
  }
  return finding;
}

Finding CheckUnusableImages(const CalibrationReport& report) {
  const double fraction = report.images > 0 ? static_cast<double>(report.unusable_images) / report.images : 0;
  const VerdictLevel level = report.unusable_images == 0               ? VerdictLevel::kGood
                             : fraction <= kUnusableFractionAcceptable ? VerdictLevel::kAcceptable
                                                                       : VerdictLevel::kPoor;
  Finding finding{
      "unusable images",
      level,
      std::to_string(report.unusable_images) + " of " + Plural(report.images, "image") + " without a usable board pose",
      "good: none, acceptable ≤ " + Figure(100 * kUnusableFractionAcceptable) + " %",
      "the board was found in every image.",
      ""};
  if (level != VerdictLevel::kGood) {
    finding.meaning = "images where the board was not found or fitted badly are left out.";
    finding.advice = "see each image's status with hexcal measure --session; keep the whole board in view and sharp";
  }
  return finding;
}

Finding CheckOutliers(const CalibrationReport& report) {
  const int readings = 6 * std::max(report.calibration_images, 1);
  const int flagged = static_cast<int>(report.outliers.size());
  const double fraction = static_cast<double>(flagged) / readings;
  const VerdictLevel level = flagged == 0                             ? VerdictLevel::kGood
                             : fraction <= kOutlierFractionAcceptable ? VerdictLevel::kAcceptable
                                                                      : VerdictLevel::kPoor;
  Finding finding{"outliers",
                  level,
                  Plural(flagged, "reading") + " of " + std::to_string(readings) + " flagged",
                  "good: none, acceptable ≤ " + Figure(100 * kOutlierFractionAcceptable) + " % of the readings",
                  "every leg reading agrees with its image's camera pose within the noise.",
                  ""};
  if (report.screening && !report.screening->screened) {
    finding.figure += " (not screened: too few images)";
  }
  if (level == VerdictLevel::kGood) return finding;
  auto by_z = [](const OutlierReading& a, const OutlierReading& b) { return std::abs(a.z) < std::abs(b.z); };
  const OutlierReading& worst = *std::max_element(report.outliers.begin(), report.outliers.end(), by_z);
  finding.meaning = "some leg readings disagree with the camera by far more than the noise: a wrong reading or image.";
  finding.advice = "check the readings of image " + worst.image +
                   (worst.legs_line ? " (legs.csv line " + std::to_string(*worst.legs_line) + ")" : "") + ", leg " +
                   std::to_string(worst.leg) + ": its residual is " + Figure(std::abs(worst.z)) + "σ";
  return finding;
}

}  // namespace hexcal::workflow

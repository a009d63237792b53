// The data findings of the verdict (calibration_verdict.h): how many poses,
// unusable images, outlier readings and the images they take out.
#include <algorithm>
#include <cmath>

#include "core/outlier_screening.h"
#include "report/verdict_checks.h"

namespace hexcal::workflow {

namespace {

// What a legs.csv row is ("image", a points session's "pose") and what measures it.
std::string Noun(const CalibrationReport& report) { return MeasurementNoun(report.instrument); }
std::string InstrumentWord(const CalibrationReport& report) {
  return report.instrument == Instrument::kPoints ? "tracker" : "camera";
}

}  // namespace

Finding CheckPoses(const CalibrationReport& report) {
  const std::string noun = Noun(report);
  const int calibration = report.calibration_images, held_out = report.held_out_images;
  VerdictLevel level = calibration >= kCalibrationImagesGood ? VerdictLevel::kGood
                       : calibration >= kMinRowsToScreen     ? VerdictLevel::kAcceptable
                                                             : VerdictLevel::kPoor;
  if (held_out > 0 && held_out < kHeldOutImagesGood) level = std::max(level, VerdictLevel::kAcceptable);
  Finding finding{"poses",
                  level,
                  Plural(calibration, "calibration " + noun) + ", " + std::to_string(held_out) + " held out",
                  "good ≥ " + std::to_string(kCalibrationImagesGood) + " calibration " + noun +
                      "s, 3 per leg parameter, and ≥ " + std::to_string(kHeldOutImagesGood) +
                      " held out; poor < " + std::to_string(kMinRowsToScreen),
                  "enough poses to fit each leg's 7 parameters with redundancy to spare.",
                  ""};
  if (calibration < kCalibrationImagesGood) {
    finding.meaning = "few poses per leg parameter: σ and the outlier screening rest on little redundancy.";
    finding.advice = "measure at least " + std::to_string(kCalibrationImagesGood - calibration) +
                     " more planned poses (hexcal plan)";
  } else if (level != VerdictLevel::kGood) {
    finding.meaning = "too few held-out poses to judge the calibration on new poses reliably.";
    finding.advice = "hold out at least " + std::to_string(kHeldOutImagesGood) + " " + noun + "s (holdout = 1 in legs.csv)";
  }
  return finding;
}

namespace {

// What the unusable-measurement finding says for each instrument.
struct UnusableWords {
  const char *aspect, *noun, *why, *all_fine, *meaning, *advice;
};

const UnusableWords& WordsFor(Instrument instrument) {
  static const UnusableWords camera{
      "unusable images", "image", " without a usable board pose", "the board was found in every image.",
      "images where the board was not found or fitted badly are left out.",
      "see each image's status with hexcal measure --session; keep the whole board in view and sharp"};
  static const UnusableWords points{  // a points session's poses (point_session.h)
      "unusable poses", "pose", " whose points do not fit", "every pose's points fitted the reflectors.",
      "poses with fewer than 3 points, an outlier point or an unknown reflector are left out.",
      "see the warnings of calibrate --session, which name each pose and why; measure it again"};
  return instrument == Instrument::kPoints ? points : camera;
}

}  // namespace

Finding CheckUnusableImages(const CalibrationReport& report) {
  const double fraction = report.images > 0 ? static_cast<double>(report.unusable_images) / report.images : 0;
  const VerdictLevel level = report.unusable_images == 0               ? VerdictLevel::kGood
                             : fraction <= kUnusableFractionAcceptable ? VerdictLevel::kAcceptable
                                                                       : VerdictLevel::kPoor;
  const UnusableWords& words = WordsFor(report.instrument);
  Finding finding{words.aspect,
                  level,
                  std::to_string(report.unusable_images) + " of " + Plural(report.images, words.noun) + words.why,
                  "good: none, acceptable ≤ " + Figure(100 * kUnusableFractionAcceptable) + " %",
                  words.all_fine,
                  ""};
  if (level != VerdictLevel::kGood) {
    finding.meaning = words.meaning;
    finding.advice = words.advice;
  }
  return finding;
}

namespace {

// The images holding a reading the screening excluded, each with those legs,
// in the report's order (legs.csv's).
std::vector<ImageClosure> LeftOutImages(const CalibrationReport& report) {
  std::vector<ImageClosure> images;
  for (const OutlierReading& o : report.outliers) {
    if (!o.excluded) continue;
    if (images.empty() || images.back().image != o.image) images.push_back({o.image, o.legs_line, false, 0, 0, true, {}});
    images.back().excluded_legs.push_back(o.leg);
  }
  return images;
}

// Readings kept in the fit although flagged (--keep-outliers): the fit rests on them.
Finding CheckKeptOutliers(const CalibrationReport& report, int kept) {
  const int readings = 6 * std::max(report.calibration_images, 1);
  const double fraction = static_cast<double>(kept) / readings;
  const VerdictLevel level = fraction <= kOutlierFractionAcceptable ? VerdictLevel::kAcceptable : VerdictLevel::kPoor;
  Finding finding{"outliers",
                  level,
                  Plural(kept, "flagged reading") + " of " + std::to_string(readings) + " kept in the fit",
                  "good: none kept, acceptable ≤ " + Figure(100 * kOutlierFractionAcceptable) + " % of the readings",
                  "some leg readings disagree with the " + InstrumentWord(report) +
                      " by far more than the noise: a wrong reading or " + Noun(report) + ".",
                  ""};
  auto by_z = [](const OutlierReading& a, const OutlierReading& b) {
    return (a.excluded ? 0 : std::abs(a.z)) < (b.excluded ? 0 : std::abs(b.z));
  };
  const OutlierReading& worst = *std::max_element(report.outliers.begin(), report.outliers.end(), by_z);
  finding.advice = "check the readings of " + Noun(report) + " " + worst.image +
                   (worst.legs_line ? " (legs.csv line " + std::to_string(*worst.legs_line) + ")" : "") + ", leg " +
                   std::to_string(worst.leg) + ": its residual is " + Figure(std::abs(worst.z)) +
                   "σ; without --keep-outliers it is left out";
  return finding;
}

}  // namespace

// Excluded readings take their image out of the registration, the fit of
// that leg and the closure (core/registration.h): the calibration rests on
// the rest. A few images so left out, each named with its cause, leave it
// good; many say the session is unreliable.
Finding CheckOutliers(const CalibrationReport& report) {
  const int kept = static_cast<int>(std::count_if(report.outliers.begin(), report.outliers.end(),
                                                  [](const OutlierReading& o) { return !o.excluded; }));
  if (kept > 0) return CheckKeptOutliers(report, kept);
  const std::vector<ImageClosure> left_out = LeftOutImages(report);
  const std::string noun = Noun(report);
  const int images = std::max(report.calibration_images, 1);
  const double fraction = static_cast<double>(left_out.size()) / images;
  const VerdictLevel level = fraction <= kLeftOutImageFractionGood         ? VerdictLevel::kGood
                             : fraction <= kLeftOutImageFractionAcceptable ? VerdictLevel::kAcceptable
                                                                           : VerdictLevel::kPoor;
  const std::string figure =
      report.outliers.empty()
          ? "no reading flagged (" + Plural(images, "calibration " + noun) + ")"
          : Plural(static_cast<int>(left_out.size()), "calibration " + noun) + " of " + std::to_string(images) +
                " left out for " + Plural(static_cast<int>(report.outliers.size()), "flagged reading");
  Finding finding{"outliers",
                  level,
                  figure,
                  "good ≤ " + Figure(100 * kLeftOutImageFractionGood) + " %, acceptable ≤ " +
                      Figure(100 * kLeftOutImageFractionAcceptable) + " % of the calibration " + noun + "s",
                  "every leg reading agrees with its " + noun + "'s " + InstrumentWord(report) + " pose within the noise.",
                  ""};
  if (report.screening && !report.screening->screened) finding.figure += " (not screened: too few " + noun + "s)";
  if (left_out.empty()) return finding;
  constexpr size_t kNamed = 3;  // in the figure; the meaning names every one
  for (size_t k = 0; k < left_out.size() && k < kNamed; ++k)
    finding.figure += std::string(k == 0 ? ": " : "; ") + ImageLabel(left_out[k]) + ", " + ShortCause(left_out[k], report.instrument);
  if (left_out.size() > kNamed) finding.figure += "; ...";
  finding.meaning = "left out of the registration, the fit and the closure:";
  for (const ImageClosure& image : left_out) finding.meaning += " " + ImageLabel(image) + ", " + LeftOutCause(image, report.instrument) + ";";
  finding.meaning.back() = '.';
  if (level != VerdictLevel::kGood)
    finding.advice = "more than " + Figure(100 * kLeftOutImageFractionGood) +
                     " % of the calibration " + noun + "s left out: check that " +
                     (report.instrument == Instrument::kPoints ? "the points file's poses" : "images") +
                     " and legs.csv rows belong together, and add poses";
  return finding;
}

}  // namespace hexcal::workflow

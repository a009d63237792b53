#include "report/verdict_checks.h"

#include <algorithm>
#include <cmath>

#include "core/csv.h"
#include "core/outlier_screening.h"

namespace hexcal::workflow {
namespace {

std::string RatioBands() {
  return "good ≤ " + Figure(kNoiseRatioGood) + "×, acceptable ≤ " + Figure(kNoiseRatioAcceptable) +
         "× the noise-predicted error";
}

// A figure over what the noise predicts, in the bands of kNoiseRatioGood and
// kNoiseRatioAcceptable; meaning and advice are the caller's.
Finding NoiseRatioFinding(const std::string& aspect, double ratio, const std::string& figure) {
  return {aspect, LevelAtMost(ratio, kNoiseRatioGood, kNoiseRatioAcceptable), figure, RatioBands(), "", ""};
}

// The held-out image with the largest position error after calibration.
std::string WorstHeldOutImage(const ValidationSummary& validation) {
  const HeldOutImage* worst = nullptr;
  for (const HeldOutImage& image : validation.per_image) {
    if (!image.position_after) continue;
    if (!worst || *image.position_after > *worst->position_after) worst = &image;
  }
  return worst ? worst->image : "";
}

std::string FkFigure(const PoseErrorStats& after, const ExpectedPoseError& expected, const std::string& unit) {
  return "position RMS " + Figure(after.position_rms) + " " + unit + " = " +
         Figure(after.position_rms / expected.position_rms) + "× expected " + Figure(expected.position_rms) + " " +
         unit + ", orientation RMS " + Figure(after.orientation_rms) +
         "° = " + Figure(after.orientation_rms / expected.orientation_rms_deg) + "× expected " +
         Figure(expected.orientation_rms_deg) + "°";
}

}  // namespace

VerdictLevel LevelAtMost(double value, double good, double acceptable) {
  if (!std::isfinite(value)) return VerdictLevel::kPoor;
  if (value <= good) return VerdictLevel::kGood;
  return value <= acceptable ? VerdictLevel::kAcceptable : VerdictLevel::kPoor;
}

VerdictLevel LevelAtLeast(double value, double good, double acceptable) {
  if (!std::isfinite(value)) return VerdictLevel::kPoor;
  if (value >= good) return VerdictLevel::kGood;
  return value >= acceptable ? VerdictLevel::kAcceptable : VerdictLevel::kPoor;
}

std::string Plural(int count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

std::string Figure(double value) { return FormatSignificant(value); }

Finding CheckFkErrors(const PoseErrorStats& after, const ExpectedPoseError& expected, const std::string& unit,
                      const std::string& worst_image, Instrument instrument) {
  const bool points = instrument == Instrument::kPoints;
  const double ratio =
      std::max(after.position_rms / expected.position_rms, after.orientation_rms / expected.orientation_rms_deg);
  Finding finding = NoiseRatioFinding("held-out error", ratio, FkFigure(after, expected, unit));
  if (finding.level == VerdictLevel::kGood) {
    finding.meaning = "the calibrated robot predicts poses it was not fitted to as well as the measurements allow.";
  } else {
    finding.meaning = "poses the fit did not see are predicted " + Figure(ratio) +
                      " times worse than the measurement noise explains: the model, the " +
                      (points ? "tracker" : "camera") + " or the noise model is off.";
    finding.advice = std::string(points ? "check the reflector file and the points' σ" : "check the camera calibration") +
                     " and the noise model in session.yaml, then add poses";
    if (!worst_image.empty())
      finding.advice += " near held-out " + std::string(MeasurementNoun(instrument)) + " " + worst_image +
                        " (its error is the largest)";
  }
  if (after.failed > 0) {
    finding.level = std::max(finding.level, VerdictLevel::kAcceptable);
    finding.figure += "; FK failed on " + Plural(after.failed, "pose");
    finding.advice += std::string(finding.advice.empty() ? "" : "; ") +
                      "look at the poses where forward kinematics did not converge (near a singularity?)";
  }
  return finding;
}

Finding CheckHeldOut(const CalibrationReport& report) {
  if (!report.validation) {
    return {"held-out error",
            VerdictLevel::kAcceptable,
            "no held-out " + std::string(MeasurementNoun(report.instrument)) + "s",
            "good: at least " + std::to_string(kHeldOutImagesGood) + " held-out " + MeasurementNoun(report.instrument) +
                "s",
            "without poses kept out of the fit nothing checks the calibrated robot on new poses.",
            "set holdout = 1 on about one row in five of legs.csv and calibrate again"};
  }
  if (!report.noise) {
    return {"held-out error",
            VerdictLevel::kAcceptable,
            "position RMS " + Figure(report.validation->after.position_rms) + " " + report.length_unit,
            "needs the noise model's prediction",
            "this report predates the record of the noise model.",
            "run hexcal calibrate --session again"};
  }
  const ExpectedPoseError expected{report.noise->position_rms, report.noise->orientation_rms_deg};
  return CheckFkErrors(report.validation->after, expected, report.length_unit, WorstHeldOutImage(*report.validation),
                       report.instrument);
}

Finding CheckClosure(const CalibrationReport& report) {
  const double ratio = report.closure_position_rms / report.noise->position_rms;
  Finding finding = NoiseRatioFinding("closure", ratio,
                                      "RMS " + Figure(report.closure_position_rms) + " " + report.length_unit + " = " +
                                          Figure(ratio) + "× expected " + Figure(report.noise->position_rms) + " " +
                                          report.length_unit);
  const bool points = report.instrument == Instrument::kPoints;
  const std::string instrument = points ? "tracker" : "camera";
  if (finding.level == VerdictLevel::kGood) {
    finding.meaning = instrument + ", registered frames and calibrated robot agree on the calibration poses.";
  } else {
    finding.meaning =
        instrument + " poses and the calibrated robot disagree beyond the noise on the poses it was fitted to.";
    finding.advice = std::string(points ? "check the reflector file and that the points are in the robot's unit"
                                        : "recalibrate the camera (intrinsics) and check the target file's tag size") +
                     " (closure RMS " +
                     Figure(report.closure_position_rms) + " " + report.length_unit +
                     "); if they are right, the noise model in session.yaml is optimistic";
  }
  return finding;
}

Finding CheckResiduals(const CalibrationReport& report) {
  auto by_factor = [](const LegFit& a, const LegFit& b) { return a.variance_factor < b.variance_factor; };
  const LegFit& lowest = *std::min_element(report.legs.begin(), report.legs.end(), by_factor);
  const LegFit& highest = *std::max_element(report.legs.begin(), report.legs.end(), by_factor);
  const double s_low = std::sqrt(lowest.variance_factor), s_high = std::sqrt(highest.variance_factor);
  const VerdictLevel high = LevelAtMost(s_high, kScatterFactorGood, kScatterFactorAcceptable);
  const VerdictLevel low = LevelAtLeast(s_low, 1 / kScatterFactorGood, 1 / kScatterFactorAcceptable);
  Finding finding{"residuals",
                  std::max(high, low),
                  "variance factor s² " + Figure(lowest.variance_factor) + "–" + Figure(highest.variance_factor) +
                      " over the legs, s " + Figure(s_low) + "–" + Figure(s_high),
                  "good: s within a factor " + Figure(kScatterFactorGood) + " of 1, acceptable within " +
                      Figure(kScatterFactorAcceptable),
                  "the residuals scatter as the noise model says.",
                  ""};
  if (high > VerdictLevel::kGood) {
    finding.meaning = "leg " + std::to_string(highest.leg) + "'s residuals are " + Figure(s_high) +
                      " times the noise model's: a model error or noisier measurements than assumed.";
    finding.advice = "check leg " + std::to_string(highest.leg) +
                     "'s readings and the camera; if they are right, raise the noise half-widths in session.yaml";
  } else if (low > VerdictLevel::kGood) {
    finding.meaning = "leg " + std::to_string(lowest.leg) + "'s residuals are " + Figure(s_low) +
                      " times the noise model's: the noise is overstated and the σ are pessimistic.";
    finding.advice = "lower the noise half-widths in session.yaml (noise:) to what the sensors achieve";
  }
  return finding;
}

}  // namespace hexcal::workflow

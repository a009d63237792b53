// The parameter findings of the verdict (calibration_verdict.h): precision,
// plausibility of the changes, the truth (demo) and the conditioning.
#include <algorithm>
#include <cmath>

#include "report/verdict_checks.h"
#include "session/results_files.h"

namespace hexcal::workflow {
namespace {

std::string ParameterLabel(const ParameterEstimate& p) { return "leg " + std::to_string(p.leg) + " " + p.name; }

// The robot's size: its largest base-joint radius (robot unit).
double RobotSize(const Robot& robot) {
  double size = 0;
  for (const Leg& leg : robot.legs) size = std::max(size, leg.a_in_base.head<2>().norm());
  return size;
}

// The largest |change|/σ: the parameter most clearly identified.
std::string MostIdentified(const std::vector<ParameterEstimate>& parameters) {
  const ParameterEstimate* best = nullptr;
  double best_ratio = 0;
  for (const ParameterEstimate& p : parameters) {
    if (!p.sigma || *p.sigma <= 0) continue;
    const double ratio = std::abs(p.estimate - p.nominal) / *p.sigma;
    if (ratio > best_ratio) best_ratio = ratio, best = &p;
  }
  if (!best) return "";
  return " The largest |change|/σ, " + Figure(best_ratio) + " (" + ParameterLabel(*best) +
         "), only says that parameter was identified and differs from nominal: not alarming by itself.";
}

}  // namespace

Finding CheckParameterSigmas(const CalibrationReport& report) {
  const std::string& unit = report.length_unit;
  const ParameterEstimate* worst = nullptr;
  int without_sigma = 0;
  for (const ParameterEstimate& p : report.parameters) {
    if (!p.sigma)
      ++without_sigma;
    else if (!worst || *p.sigma > *worst->sigma)
      worst = &p;
  }
  const double required = report.noise->position_rms;
  const std::string bands = "good: σ ≤ " + Figure(kSigmaRatioGood) + "×, acceptable ≤ " +
                            Figure(kSigmaRatioAcceptable) + "× the noise-predicted error " + Figure(required) + " " +
                            unit;
  if (without_sigma > 0 || !worst) {
    return {"parameters (σ)",
            VerdictLevel::kPoor,
            std::to_string(without_sigma) + " parameters without σ",
            bands,
            "a leg with as many poses as parameters is fitted exactly and its precision is unknown.",
            "add poses (hexcal plan) and calibrate again"};
  }
  const double ratio = *worst->sigma / required;
  Finding finding{"parameters (σ)",
                  LevelAtMost(ratio, kSigmaRatioGood, kSigmaRatioAcceptable),
                  "largest σ " + Figure(*worst->sigma) + " " + unit + " (" + ParameterLabel(*worst) +
                      ") = " + Figure(ratio) + "× the noise-predicted error",
                  bands,
                  "no parameter's uncertainty moves a predicted pose by more than twice the measurement noise.",
                  ""};
  if (finding.level != VerdictLevel::kGood) {
    finding.meaning = ParameterLabel(*worst) + " is poorly identified: its uncertainty alone moves poses by more " +
                      "than the measurement noise.";
    finding.advice =
        "add poses that move leg " + std::to_string(worst->leg) +
        " over its whole stroke and tilt the platform (hexcal plan picks them); if the held-out error is poor "
        "too, check the noise model first";
  }
  return finding;
}

Finding CheckParameterChanges(const CalibrationReport& report) {
  const std::string& unit = report.length_unit;
  const ParameterEstimate* largest = &report.parameters.front();
  for (const ParameterEstimate& p : report.parameters) {
    if (std::abs(p.estimate - p.nominal) > std::abs(largest->estimate - largest->nominal)) largest = &p;
  }
  const double change = std::abs(largest->estimate - largest->nominal), size = RobotSize(report.robot);
  const double fraction = size > 0 ? change / size : 0;
  Finding finding{"parameters (change)",
                  LevelAtMost(fraction, kChangeFractionGood, kChangeFractionAcceptable),
                  "largest change " + Figure(change) + " " + unit + " (" + ParameterLabel(*largest) +
                      ") = " + Figure(100 * fraction) + " % of the robot's size " + Figure(size) + " " + unit,
                  "good ≤ " + Figure(100 * kChangeFractionGood) + " %, acceptable ≤ " +
                      Figure(100 * kChangeFractionAcceptable) + " % of the size",
                  "the changes from nominal are of the size of build tolerances and the registration's gauge." +
                      MostIdentified(report.parameters),
                  ""};
  if (finding.level == VerdictLevel::kGood) return finding;
  finding.meaning = ParameterLabel(*largest) + " moved by more than a build error explains.";
  finding.advice = "check the nominal robot file (values, unit " + unit + ") and the readings' zero offsets";
  // A focal or scale error moves the registered frames, and the parameters
  // follow them: the camera is the suspect, not the robot file.
  const std::optional<PixelEstimateSummary> scale = LargestScaleChange(report);
  if (scale && std::abs(scale->estimate / scale->file_value - 1) > kScaleChangeGood) {
    finding.meaning += " " + ScaleChangeText(*scale) + ": the frames were registered with it.";
    finding.advice = scale->name == "target_scale"
                         ? "check the target file's tag size, then calibrate again"
                         : "recalibrate the camera (hexcal intrinsics) or make " + ResultsName(kFittedCamera) +
                               " the session's camera, then calibrate again; if the changes stay, check the nominal "
                               "robot file";
  }
  return finding;
}

Finding CheckTruth(const VerdictTruth& truth) {
  Finding finding{"parameters (truth)",
                  LevelAtLeast(truth.within_3sigma, kWithin3SigmaGood, kWithin3SigmaAcceptable),
                  Figure(100 * truth.within_3sigma) + " % of " + std::to_string(truth.with_sigma) +
                      " parameters within 3σ of the true robot",
                  "good ≥ " + Figure(100 * kWithin3SigmaGood) + " %, acceptable ≥ " +
                      Figure(100 * kWithin3SigmaAcceptable) + " %; 99.7 % expected",
                  "the stated σ describe the real errors.",
                  ""};
  if (finding.level != VerdictLevel::kGood) {
    finding.meaning = "the σ understate the real errors: the noise model is optimistic or the model is biased.";
    finding.advice = "raise the noise half-widths in session.yaml or look for a bias (camera, registration)";
  }
  return finding;
}

std::optional<Finding> CheckConditioning(const CalibrationReport& report) {
  const LegFit* worst = nullptr;
  for (const LegFit& leg : report.legs) {
    if (leg.condition_number && (!worst || *leg.condition_number > *worst->condition_number)) worst = &leg;
  }
  if (!worst) return std::nullopt;
  const double condition = *worst->condition_number;
  Finding finding{"identifiability",
                  LevelAtMost(condition, kConditionGood, kConditionAcceptable),
                  "largest condition number " + Figure(condition) + ", leg " + std::to_string(worst->leg),
                  "good ≤ " + Figure(kConditionGood) + ", acceptable ≤ " + Figure(kConditionAcceptable),
                  "the poses constrain every direction of each leg's 7 parameters.",
                  ""};
  if (finding.level != VerdictLevel::kGood) {
    finding.meaning = "leg " + std::to_string(worst->leg) +
                      "'s poses barely constrain one combination of its parameters: noise is amplified along it.";
    finding.advice = "plan poses with hexcal plan (IOOPS) instead of random or repeated ones";
  }
  return finding;
}

}  // namespace hexcal::workflow

// A finding of the verdict on a calibration (calibration_verdict.h) and the
// thresholds its levels come from (docs/calibration.md, "Verdict"): what the
// checks of verdict_checks.h return and MakeVerdict collects. Apart from
// calibration_verdict.h so that the checks do not include the verdict that
// calls them (issue 37: the two included each other).
//
//   Finding finding{"held-out error", VerdictLevel::kAcceptable, "2.6 × the noise", "good ≤ 2, acceptable ≤ 4"};
//   if (ratio > kNoiseRatioAcceptable) finding.level = VerdictLevel::kPoor;
#pragma once

#include <string>

namespace hexcal::workflow {

enum class VerdictLevel { kGood = 0, kAcceptable = 1, kPoor = 2 };

// Held-out FK error (and closure) over what the noise predicts (expected_error.h):
// ratio² = 1 + (unexplained error / noise)², so 2 allows an unexplained error
// of √3 ≈ 1.7 times the noise, 4 one of √15 ≈ 3.9 times.
constexpr double kNoiseRatioGood = 2, kNoiseRatioAcceptable = 4;
// s = √(variance factor) of a leg: 1 when the noise model matches the residuals.
// For N − 7 ≥ 14 degrees of freedom the 99.9 % chi-square band of s lies
// inside [1/2, 2]; beyond a factor 4 the σ are off by that much.
constexpr double kScatterFactorGood = 2, kScatterFactorAcceptable = 4;
// Largest parameter σ over the noise-predicted FK position error. A parameter
// error δ moves a predicted pose by about δ, so the bands are those of the
// held-out ratio: up to 2 the parameters add at most √3 × the noise.
constexpr double kSigmaRatioGood = 2, kSigmaRatioAcceptable = 4;
// Largest |change| over the robot's size (largest base-joint radius). The
// changes hold the build errors (well under 1 % of the size) and the gauge:
// the frames are registered with the nominal robot, so a shift of all joints
// together of a few per cent is absorbed (2.75 % in the demo). Above 5 %
// suspect the nominal file, above 20 % a wrong unit or robot.
constexpr double kChangeFractionGood = 0.05, kChangeFractionAcceptable = 0.20;
// The calibration from pixels' focal lengths and target scale against the
// files': 0.5 % is about what a good intrinsic calibration guarantees (TUM
// VI's published f against a refit differ by 0.2 %); beyond 5 % the files
// are not this camera's or board's.
constexpr double kScaleChangeGood = 0.005, kScaleChangeAcceptable = 0.05;
// Demo only: fraction of parameters within 3σ of the truth (99.7 % expected).
constexpr double kWithin3SigmaGood = 0.90, kWithin3SigmaAcceptable = 0.75;
// σ_max/σ_min of a leg's weighted identification Jacobian: noise is amplified
// that much more along the weakest direction than the strongest; 1e4 is where
// core/calibration.h reports unidentifiable directions (weak_direction_ratio).
constexpr double kConditionGood = 1e3, kConditionAcceptable = 1e4;
// Calibration images: 3 per parameter of a leg for good; fewer than
// kMinRowsToScreen (7 + 3) cannot be screened for outliers: poor.
constexpr int kCalibrationImagesGood = 21;
// Held-out images: the RMS of fewer than 5 errors scatters by over ±30 %.
constexpr int kHeldOutImagesGood = 5;
// Images without a usable board pose, as a fraction of all images.
constexpr double kUnusableFractionAcceptable = 0.25;
// Leg readings flagged as outliers and kept in the fit (--keep-outliers), as
// a fraction of all calibration readings: any is at best acceptable.
constexpr double kOutlierFractionAcceptable = 0.05;
// Calibration images left out for an excluded reading (a wrong reading, a
// swapped image), each named: 1 in 20 leaves the fit on the rest good, more
// than 3 in 20 says the session's images and readings do not belong together.
constexpr double kLeftOutImageFractionGood = 0.05, kLeftOutImageFractionAcceptable = 0.15;

struct Finding {
  std::string aspect;  // "held-out error", "residuals", "parameters (σ)", ...
  VerdictLevel level = VerdictLevel::kGood;
  std::string figure;     // the value compared, with units
  std::string threshold;  // what it was compared with
  std::string meaning;    // one sentence
  std::string advice;     // what to do; empty when good
};

// What only the demo knows: the calibration against the true robot.
struct VerdictTruth {
  double within_3sigma = 0;  // fraction of the parameters with a σ
  int with_sigma = 0;
};

}  // namespace hexcal::workflow

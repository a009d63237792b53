// Whether an intrinsic calibration can be trusted, and if not, why.
//
// A calibration whose residuals are far above what detected corners scatter
// by (a few hundredths to a few tenths of a pixel) is not a camera: the
// target was described wrongly (layout, spacing, first id, border), its size
// in the wrong unit, or the lens needs another model. cv::calibrateCamera
// still returns numbers for it (a 6 × 6 grid described with spacing 0.5
// instead of 0.3 gives RMS 4.7 px and plausible-looking focal lengths), so
// the check is made here and the camera file is not written.
//
//   if (Status s = CheckIntrinsicsFit(result, target, options.max_rms_px); !s.ok()) return s;
#pragma once

#include <string>
#include <vector>

#include "core/status.h"
#include "vision/camera.h"
#include "vision/intrinsics_result.h"
#include "vision/target.h"

namespace hexcal {

// OK when the RMS over every used corner is at most `max_rms_px`; else a
// bad-input error with the diagnosis: whether every view fits badly
// (systematic: the target's description, its unit or the camera model) or a
// few do (those views, named), and what the target file says the board is.
Status CheckIntrinsicsFit(const IntrinsicsResult& result, const Target& target, double max_rms_px);

// Two cameras calibrated from disjoint halves of the views, compared: the
// rays of a 16 × 12 grid of pixels (unprojected by `full`) projected by each
// (pixel difference, RMS and max), and fx, fy, cx, cy in units of the halves'
// combined σ (when both have σ: std_dev in Camera::ParameterNames() order).
CrossValidation CompareHalves(const Camera& full, const Camera& a, const std::vector<double>& sigma_a,
                              const Camera& b, const std::vector<double>& sigma_b);

// The cross-validation's judgement (docs/vision.md, "Cross-validation"):
// good when the halves' projections of the image's rays differ by at most
// kCrossHalvesGoodPx RMS and, where the model gives σ, fx fy cx cy by at most
// kCrossSigmaGood of their combined σ; poor otherwise.
// 0.5 px: ten times the corner scatter of a sharp view (0.02–0.05 px), and
// half the --max-rms a whole fit may reach; a camera that moves a projection
// by more with the choice of views is not determined by them.
// 3 σ: four independent |N(0, 1)| reach it together about 1 % of the time;
// beyond it the σ are too small for the data.
constexpr double kCrossHalvesGoodPx = 0.5;
constexpr double kCrossSigmaGood = 3;
bool CrossValidationGood(const CrossValidation& cross);

// "cross-validation (16 + 16 views): the halves differ by 0.012 px RMS (0.03
// px max) over the image, fx fy cx cy at most 0.8 sigma apart: good (within
// 0.5 px RMS and 3 sigma)", or ": poor (good is within ...); " and what to do.
std::string DescribeCrossValidation(const CrossValidation& cross);

// A used view whose RMS is over `factor` times the median view's, which the
// outlier rule kept (it also asks for IntrinsicsOptions::outlier_min_rms_px):
// "view_0012.png fits 14x worse than the median view (RMS 0.67 px, median
// 0.048 px): check it (motion blur, a bent board)"; empty when none is.
std::string DescribeWorstView(const IntrinsicsResult& result, double factor);

}  // namespace hexcal

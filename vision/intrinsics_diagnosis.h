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

#include "core/status.h"
#include "vision/intrinsics.h"
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

// "halves differ by 0.012 px RMS (0.03 px max) over the image, 0.8 sigma at most"
std::string DescribeCrossValidation(const CrossValidation& cross);

}  // namespace hexcal

// The screening of the leg readings in a joint fit (the calibrations from
// pixels and from points; docs/calibration.md, "Outliers"): a robust fit
// first (a Cauchy loss of kScreeningCauchyScale σ_L), then least squares
// without the outliers (or with them, `keep`), which are named in the
// result's legs. `fit(input, options)` runs the calibration; `rows(input)`
// is its observations (images or poses), each with `leg_excluded`.
//
//   StatusOr<PixelCalibrationResult> fit = ScreenedJointFit(
//       input, options, screening,
//       [&](const PixelCalibrationInput& in, const PixelCalibrationOptions& o) { return CalibrateFromPixels(in, o, hooks); },
//       [](PixelCalibrationInput& in) -> std::vector<PixelImage>& { return in.images; });
#pragma once

#include "core/outlier_screening.h"

namespace hexcal::workflow {

template <typename Input, typename Options, typename Fit, typename Rows>
auto ScreenedJointFit(Input input, Options options, const OutlierScreening& screening, Fit fit, Rows rows)
    -> decltype(fit(input, options)) {
  if (!screening.enabled) return fit(input, options);
  options.leg_cauchy_scale = kScreeningCauchyScale;
  auto robust = fit(input, options);
  if (!robust.ok()) return robust.status();
  const auto outliers = ScreenJointFitReadings(robust->leg_z, screening, options.leg_sigma);
  for (int i = 0; i < kNumLegs; ++i)
    for (const RowOutlier& o : outliers[i]) rows(input)[o.measurement].leg_excluded[i] = o.excluded;
  options.leg_cauchy_scale = 0;
  auto result = fit(input, options);
  if (!result.ok()) return result.status();
  for (int i = 0; i < kNumLegs; ++i) result->calibration.legs[i].outliers = outliers[i];
  return result;
}

}  // namespace hexcal::workflow

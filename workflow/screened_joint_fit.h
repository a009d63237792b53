// The screening of the leg readings in a joint fit (the calibrations from
// pixels and from points; docs/calibration.md, "Outliers"): a robust fit
// first (a Cauchy loss of kScreeningCauchyScale σ_L), then least squares
// without the outliers (or with them, `keep`), which are named in the
// result's legs. `fit` runs the calibration; `rows` is the input's
// observations (images or poses), each with `leg_excluded`.
//
//   StatusOr<PixelCalibrationResult> fit = ScreenedJointFit(
//       input, options, screening, &CalibrateFromPixels, &PixelCalibrationInput::images, hooks);
#pragma once

#include <vector>

#include "core/job_hooks.h"
#include "core/outlier_screening.h"
#include "core/status.h"

namespace hexcal::workflow {

template <typename Input, typename Options, typename Result, typename Row>
StatusOr<Result> ScreenedJointFit(Input input, Options options, const OutlierScreening& screening,
                                  StatusOr<Result> (*fit)(const Input&, const Options&, const JobHooks&),
                                  std::vector<Row> Input::*rows, const JobHooks& hooks) {
  if (!screening.enabled) return fit(input, options, hooks);
  options.leg_cauchy_scale = kScreeningCauchyScale;
  StatusOr<Result> robust = fit(input, options, hooks);
  if (!robust.ok()) return robust.status();
  const auto outliers = ScreenJointFitReadings(robust->leg_z, screening, options.leg_sigma);
  for (int i = 0; i < kNumLegs; ++i)
    for (const RowOutlier& o : outliers[i]) (input.*rows)[o.measurement].leg_excluded[i] = o.excluded;
  options.leg_cauchy_scale = 0;
  StatusOr<Result> result = fit(input, options, hooks);
  if (!result.ok()) return result.status();
  for (int i = 0; i < kNumLegs; ++i) result->calibration.legs[i].outliers = outliers[i];
  return result;
}

}  // namespace hexcal::workflow

#include "core/calibration_types.h"

#include <cmath>

namespace hexcal {

std::optional<RobustLoss> ParseRobustLoss(const std::string& text) {
  if (text == "none") return RobustLoss::kNone;
  if (text == "huber") return RobustLoss::kHuber;
  if (text == "cauchy") return RobustLoss::kCauchy;
  return std::nullopt;
}

const char* RobustLossName(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "?";
}

const OptionTable<CalibrationOptions>& CalibrationOptionSpecs() {
  static const OptionTable<CalibrationOptions> table = [] {
    using Options = CalibrationOptions;
    std::vector<std::string> losses;
    for (RobustLoss kind : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy})
      losses.push_back(RobustLossName(kind));
    return OptionTable<Options>{
        ChoiceOption<Options>(
            "loss", "Robust loss", OptionType::kChoice, losses, "robust loss of the residuals, from loss_scale on",
            [](const Options& o) { return std::string(RobustLossName(o.loss)); },
            [](Options& o, const std::string& v) { o.loss = *ParseRobustLoss(v); }),
        NumberOption<Options>("loss_scale", "Loss scale", OptionType::kNumber, "", 1e-9, 1e9,
                              "where the loss starts: a leg-length error (robot unit), or, weighted, a number of "
                              "standard deviations",
                              [](Options& o) -> double& { return o.loss_scale; }),
        NumberOption<Options>("weighted", "Weighted", OptionType::kFlag, "", 0, 1,
                              "weight each residual by its standard deviation under the noise model",
                              [](Options& o) -> bool& { return o.weighted; })};
  }();
  return table;
}

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    *error = message;
    return false;
  };
  if (Status s = CheckOptionRanges(CalibrationOptionSpecs(), *this); !s.ok()) return fail(s.message());
  if (max_iterations < 1) return fail("max_iterations must be at least 1");
  if (!(function_tolerance > 0) || !(parameter_tolerance > 0)) return fail("solver tolerances must be positive");
  if (!(rank_tolerance > 0 && rank_tolerance < 1)) return fail("rank_tolerance must be in (0, 1)");
  if (!(weak_direction_ratio >= 0 && weak_direction_ratio < 1)) return fail("weak_direction_ratio must be in [0, 1)");
  if (!(correlation_threshold > 0 && correlation_threshold <= 1)) {
    return fail("correlation_threshold must be in (0, 1]");
  }
  if (num_threads < 0) return fail("num_threads must be >= 0 (0 = every core)");
  if (!outliers.IsValid(error)) return false;
  if (outliers.enabled && !weighted) {
    return fail("outlier screening needs weighted residuals: z is in standard deviations of the noise model");
  }
  if (outliers.enabled && loss != RobustLoss::kNone) {
    return fail("outlier screening makes its own robust fit: use loss none with it");
  }
  if (weighted) {
    if (!noise.IsValid(error)) return false;
    if (noise.position == 0 && noise.angle_deg == 0 && noise.leg == 0) {
      return fail("weighting needs a noise model with at least one non-zero level");
    }
  }
  return true;
}

}  // namespace hexcal

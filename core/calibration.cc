#include "core/calibration.h"

#include <cassert>
#include <cmath>

#include "core/calibration_leg.h"
#include "core/csv.h"
#include "core/parallel.h"
#include "core/reading_units.h"

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

const char* ParameterName(int k) {
  static const char* names[kParamsPerLeg] = {"ax", "ay", "az", "bx", "by", "bz", "l"};
  assert(k >= 0 && k < kParamsPerLeg);
  return names[k];
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

ParameterVector CalibrationResult::Estimates() const {
  ParameterVector p;
  for (int i = 0; i < kNumLegs; ++i) p.segment<kParamsPerLeg>(kParamsPerLeg * i) = legs[i].estimate;
  return p;
}

ParameterVector CalibrationResult::StdDevs() const {
  ParameterVector p;
  for (int i = 0; i < kNumLegs; ++i) p.segment<kParamsPerLeg>(kParamsPerLeg * i) = legs[i].std_dev;
  return p;
}

namespace {

// Readings far outside the stroke are not sensor noise but, most often, a file
// in another length unit than the robot's (mm readings for a cm robot are ten
// times too long): calibrating them would give parameters of another robot.
// "Far" is more than one stroke length beyond either end.
Status CheckReadingsInStroke(const Robot& nominal, const std::vector<Measurement>& measurements) {
  std::vector<LegReadings> readings;
  for (const Measurement& m : measurements) readings.push_back(m.legs);
  if (Status s = CheckReadingsUnit(nominal, readings, "measurement"); !s.ok()) return s;
  for (size_t j = 0; j < measurements.size(); ++j) {
    for (int i = 0; i < kNumLegs; ++i) {
      const Leg& leg = nominal.legs[i];
      const double span = leg.stroke_max - leg.stroke_min;
      const double reading = measurements[j].legs[i];
      if (reading >= leg.stroke_min - span && reading <= leg.stroke_max + span) continue;
      const char* unit = LengthUnitName(nominal.length_unit);
      return Status::BadInput("measurement " + std::to_string(j + 1) + ": L" + std::to_string(i + 1) + " = " +
                              FormatNumber(reading) + " is far outside the stroke [" + FormatNumber(leg.stroke_min) +
                              ", " + FormatNumber(leg.stroke_max) + "] " + unit + " of robot '" + nominal.name +
                              "'; are the readings in " + unit + "?");
    }
  }
  return Status::Ok();
}

}  // namespace

Status CheckCalibrationInput(const Robot& nominal, const std::vector<Measurement>& measurements,
                             const CalibrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput("calibration options: " + error);
  if (!ParametersOf(nominal).allFinite()) {
    return Status::BadInput("robot '" + nominal.name + "': kinematic parameters are not finite");
  }
  if (measurements.size() < static_cast<size_t>(kParamsPerLeg)) {
    return Status::BadInput("calibration needs at least 7 measurements (7 parameters per leg), got " +
                            std::to_string(measurements.size()));
  }
  for (size_t j = 0; j < measurements.size(); ++j) {
    if (!measurements[j].pose.allFinite() || !measurements[j].legs.allFinite()) {
      return Status::BadInput("measurement " + std::to_string(j + 1) + ": pose or leg readings are not finite");
    }
  }
  return CheckReadingsInStroke(nominal, measurements);
}

StatusOr<CalibrationResult> Calibrate(const Robot& nominal, const std::vector<Measurement>& measurements,
                                      const CalibrationOptions& options, const JobHooks& hooks) {
  if (Status s = CheckCalibrationInput(nominal, measurements, options); !s.ok()) return s;
  std::vector<Pose> poses;
  poses.reserve(measurements.size());
  for (const Measurement& m : measurements) poses.push_back(nominal.PoseFromVector(m.pose));
  std::vector<LegData> data;
  for (int i = 0; i < kNumLegs; ++i) {
    StatusOr<LegData> leg = MakeLegData(nominal, i, measurements, poses, options);
    if (!leg.ok()) return leg.status();
    if (Status s = CheckRank(i, *leg, LegParametersOf(nominal.legs[i]), options); !s.ok()) return s;
    data.push_back(std::move(*leg));
  }
  if (hooks.Cancelled()) return Status::Cancelled();

  std::vector<std::optional<StatusOr<LegCalibration>>> legs(kNumLegs);
  const bool finished = ParallelFor(
      kNumLegs, options.num_threads,
      [&](int i, int) {
        const LegParameters start = LegParametersOf(nominal.legs[i]);
        legs[i] = options.outliers.enabled ? CalibrateLegScreened(i, data[i], start, options, hooks)
                                           : CalibrateLeg(i, data[i], start, options, hooks);
      },
      hooks);
  if (!finished) return Status::Cancelled();

  CalibrationResult result;
  result.num_measurements = static_cast<int>(measurements.size());
  for (int i = 0; i < kNumLegs; ++i) {
    if (legs[i]->status().cancelled()) return legs[i]->status();
  }
  for (int i = 0; i < kNumLegs; ++i) {
    if (!legs[i]->ok()) return legs[i]->status();
    result.legs[i] = std::move(legs[i]->value());
  }
  result.robot = WithParameters(nominal, result.Estimates());
  return result;
}

}  // namespace hexcal

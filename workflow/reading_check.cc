#include "workflow/reading_check.h"

#include <algorithm>
#include <cmath>

#include "core/csv.h"
#include "core/session.h"
#include "devices/controller.h"
#include "session/session_models.h"

namespace hexcal::workflow {
namespace {

std::string Number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (std::abs(value) >= 1e6) return FormatNumber(value);
  return FormatNumber(std::round(value * 1e6) / 1e6);
}

}  // namespace

ReadingCheck MakeReadingCheck(Robot robot, const NoiseModel& noise) {
  const std::string unit = LengthUnitName(robot.length_unit);
  const double floor = kFollowingErrorFloorMetres / MetresPerUnit(robot.length_unit);
  const double from_noise = kReadingNoiseFactor * noise.leg;
  ReadingCheck check{std::move(robot), std::max(from_noise, floor), ""};
  check.basis = from_noise >= floor
                    ? Number(kReadingNoiseFactor) + " x the session's leg noise " + Number(noise.leg) + " " + unit
                    : "the floor for a controller's following error, " + Number(floor) + " " + unit;
  return check;
}

StatusOr<ReadingCheck> SessionReadingCheck(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  if (!robot.ok()) return robot.status();
  return MakeReadingCheck(std::move(*robot), config->noise);
}

Status CheckReadings(const ReadingCheck& check, const std::string& pose_name, const Vector6d& pose,
                     const LegReadings& readings) {
  const std::string unit = " " + std::string(LengthUnitName(check.robot.length_unit));
  const std::string where = pose_name + " at " + PoseText(pose);
  const LegReadings expected = InverseKinematics(check.robot, check.robot.PoseFromVector(pose));
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = check.robot.legs[i];
    const std::string leg_text = where + ": leg " + std::to_string(i + 1) + " read " + Number(readings[i]) + unit;
    if (!std::isfinite(readings[i])) return Status::Failed(leg_text + ", not a number; nothing recorded for this pose");
    if (readings[i] < leg.stroke_min - check.tolerance || readings[i] > leg.stroke_max + check.tolerance)
      return Status::Failed(leg_text + ", outside its stroke [" + Number(leg.stroke_min) + ", " +
                            Number(leg.stroke_max) + "]" + unit + " (the controller's units or scale?); " +
                            "nothing recorded for this pose");
    if (std::abs(readings[i] - expected[i]) > check.tolerance)
      return Status::Failed(leg_text + " where the commanded pose needs " + Number(expected[i]) + unit + ", " +
                            Number(std::abs(readings[i] - expected[i])) + unit + " apart, more than " +
                            Number(check.tolerance) + unit + " (" + check.basis + "); nothing recorded for this pose");
  }
  return Status::Ok();
}

double TypedTolerance(const ReadingCheck& check, int leg) {
  const Leg& stroke = check.robot.legs[leg];
  return std::max(kTypedReadingStrokeShare * (stroke.stroke_max - stroke.stroke_min), check.tolerance);
}

Status CheckTypedReading(const ReadingCheck& check, const std::string& where, int leg, double value,
                         const std::optional<Vector6d>& commanded) {
  const std::string unit = " " + std::string(LengthUnitName(check.robot.length_unit));
  const Leg& stroke = check.robot.legs[leg];
  const double tolerance = TypedTolerance(check, leg);
  const std::string reading = where + ": L" + std::to_string(leg + 1) + " = " + Number(value);
  if (!std::isfinite(value)) return Status::BadInput(reading + " is not a finite number; not saved");
  if (value < stroke.stroke_min - tolerance || value > stroke.stroke_max + tolerance)
    return Status::BadInput(reading + unit + " is outside leg " + std::to_string(leg + 1) + "'s stroke [" +
                            Number(stroke.stroke_min) + ", " + Number(stroke.stroke_max) + "]" + unit +
                            "; not saved (a typo, or a reading in another unit?)");
  if (!commanded) return Status::Ok();
  const double needed = InverseKinematics(check.robot, check.robot.PoseFromVector(*commanded))[leg];
  if (std::abs(value - needed) <= tolerance) return Status::Ok();
  return Status::BadInput(reading + unit + " is " + Number(std::abs(value - needed)) + unit + " from the " +
                          Number(needed) + unit + " the commanded pose needs, more than " + Number(tolerance) + unit +
                          " (" + Number(100 * kTypedReadingStrokeShare) +
                          " % of the stroke); not saved (another pose's reading, swapped legs or a typo?)");
}

Status CheckTypedReadings(const ReadingCheck& check, const std::string& where, const LegReadings& readings,
                          const std::optional<Vector6d>& commanded) {
  for (int i = 0; i < kNumLegs; ++i)
    if (Status s = CheckTypedReading(check, where, i, readings[i], commanded); !s.ok()) return s;
  return Status::Ok();
}

}  // namespace hexcal::workflow

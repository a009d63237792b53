// The calibrated robot file: the robot YAML of docs/robot-file.md with the
// calibrated parameters, followed by a `calibration:` section that says what
// produced them and how well they are known (docs/calibration.md). LoadRobot
// reads the robot and ignores the section, so the file works wherever a robot
// is expected.
//
//   calibration:
//     date: "2026-11-22T10:40:12Z"
//     nominal_robot: "inria-left-hand"
//     measurements: {path: "m.csv", count: 44}
//     options: {loss: none, loss_scale: 1, weighted: false, noise: {...}, max_iterations: 100}
//     length_unit: cm
//     legs:
//       - {sigma_a: [..], sigma_b: [..], sigma_l: .., residual_rms: .., variance_factor: ..,
//          iterations: 6, termination: "CONVERGENCE", unidentifiable_directions: 0}
//
//   CalibrationInputs inputs{"inria-left-hand", "m.csv", options, CurrentUtcTimestamp()};
//   Status saved = SaveCalibratedRobot("calibrated.yaml", *result, inputs);
#pragma once

#include <string>

#include "core/calibration.h"

namespace hexcal {

struct CalibrationInputs {
  std::string nominal_robot;      // the robot file or preset the calibration started from
  std::string measurements_path;  // the measurements file
  CalibrationOptions options;
  std::string date;  // ISO 8601 UTC, e.g. from CurrentUtcTimestamp()
};

// "2026-11-22T10:40:12Z"
// The time now in UTC, ISO 8601 ("2026-12-06T05:20:00Z") or in `format`
// (strftime's; "%Y%m%dT%H%M%SZ" for a folder name).
std::string CurrentUtcTimestamp(const char* format = "%Y-%m-%dT%H:%M:%SZ");

// RobotToYaml(result.robot) plus the calibration section.
std::string CalibratedRobotToYaml(const CalibrationResult& result, const CalibrationInputs& inputs);

// CalibratedRobotToYaml written atomically.
Status SaveCalibratedRobot(const std::string& path, const CalibrationResult& result, const CalibrationInputs& inputs);

}  // namespace hexcal

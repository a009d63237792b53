// Robot files: the YAML description of a robot, read strictly and written so
// that a save/load round trip gives back the same doubles. Full reference:
// docs/robot-file.md.
//
//   name: inria-left-hand
//   length_unit: cm        # mm | cm | m; every length in the file and in pose files
//   euler: xyz             # xyz: R = Rz(q3)·Ry(q2)·Rx(q1); zyx: R = Rx(q3)·Ry(q2)·Rz(q1)
//   legs:                  # exactly six: a in base, b in platform, offset l, stroke of L
//     - {a: [-9.7, 9.1, 0], b: [-3, 7.3, 0], l: 52.2496, stroke: [0, 3.5]}
//     ...
//   limits:                # optional, and so is each key
//     base_joint_max_deg: 40        # (0, 180)
//     platform_joint_max_deg: 40    # (0, 180)
//     leg_min_distance: 0.5         # >= 0, length unit
//     pose_box: {x: [-5, 5], z: [50, 57], q1: [-20, 20]}   # any subset of x y z q1 q2 q3
//   calibration: {...}     # optional, written by `hexcal calibrate`; ignored here
//
// Every problem is reported as "robot file '<source>': <key path>: <problem>",
// e.g. "robot file 'bad.yaml': legs[2].stroke: min (3.5) must be less than max (0)".
//
//   StatusOr<Robot> robot = LoadRobot("inria-left-hand");  // a file path or a preset name
//   if (!robot.ok()) { std::cerr << robot.status().message() << "\n"; return 2; }
//   Status saved = SaveRobot(*robot, "robot.yaml");
#pragma once

#include <string>
#include <vector>

#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

// Parses and validates robot YAML; `source` (usually the path) names it in
// error messages.
StatusOr<Robot> ParseRobotYaml(const std::string& text, const std::string& source);

// Loads the file at `path_or_preset` if it exists, else the embedded preset of
// that name (see PresetNames()); an existing file wins over a preset.
StatusOr<Robot> LoadRobot(const std::string& path_or_preset);

// Readable YAML in the format above; numbers are written with FormatNumber, so
// ParseRobotYaml(RobotToYaml(robot)) reproduces every double exactly.
// The `calibration` block is not part of Robot and is not written.
std::string RobotToYaml(const Robot& robot);

// RobotToYaml written with WriteFileAtomically.
Status SaveRobot(const Robot& robot, const std::string& path);

// Names of the presets compiled into the binary, sorted.
std::vector<std::string> PresetNames();

}  // namespace hexcal

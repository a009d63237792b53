// The virtual laboratory of `hexcal demo` (docs/session.md, "hexcal demo"):
// a hidden true robot (the nominal one with every parameter moved), a camera
// fixed above the platform and the target fixed on it, both at frames the
// calibration does not know, and the recording of a session folder at given
// poses: rendered images (vision/renderer.h) and noisy leg readings.
//
//   DemoScene scene = MakeDemoScene(nominal, camera, target, DemoSceneOptions{});
//   Status recorded = RecordDemoSession(scene, "inria-left-hand", "sim-4.2mm-1024x768",
//                                       planned, held_out, "demo", progress);
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/noise_model.h"
#include "core/planning_model.h"
#include "core/robot.h"
#include "core/status.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::workflow {

struct DemoSceneOptions {
  double perturb_m = 0.0005;       // ± on each of the 42 parameters of the true robot, metres
  double camera_distance_m = 0.7;  // camera above the centre of the sampling box
  // Session noise model (half-widths): the camera pose and the leg readings.
  double position_noise_m = 0.00005, angle_noise_deg = 0.02, leg_noise_m = 0.00001;
  uint64_t seed = 1;  // true robot, readings noise, image noise
};

struct DemoScene {
  Robot nominal, truth;
  Camera camera;
  Target target;
  Pose base_from_camera;      // true X, robot unit
  Pose platform_from_target;  // true Y, robot unit
  NoiseModel noise;           // robot unit; the readings are drawn with `noise.leg`
  MeasurementConstraints view;  // the target's centre in the camera's view, for the planner
  uint64_t seed = 1;
};

DemoScene MakeDemoScene(const Robot& nominal, const Camera& camera, const Target& target,
                        const DemoSceneOptions& options);

// Writes the hidden truth to DIR/truth/: the true robot (robot.yaml) and the
// true frames (frames.yaml, robot unit, degrees, Euler xyz), for comparing a
// calibration with it. A folder with truth/frames.yaml counts as a demo
// folder (`hexcal demo --force` may replace it).
Status WriteSceneTruth(const DemoScene& scene, const std::string& dir);

// Initialises the session folder DIR (hexcal session init) with the robot and
// camera names as given (a preset or a path) and records one
// image and one legs.csv row per pose: `planned` for the calibration, then
// `held_out` with holdout = 1. The hidden truth is
// written to DIR/truth/ (robot.yaml, frames.yaml) for the comparison.
Status RecordDemoSession(const DemoScene& scene, const std::string& robot_name, const std::string& camera_name,
                         const std::vector<Vector6d>& planned,
                         const std::vector<Vector6d>& held_out, const std::string& dir,
                         const std::function<void(int, int)>& progress);

}  // namespace hexcal::workflow

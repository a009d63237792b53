// The session folder: one calibration job on disk, shared by the CLI and the GUI.
//
//   DIR/session.yaml       robot, camera, target, registered frames, noise model
//   DIR/plan.csv           the planned poses (hexcal plan --out), optional
//   DIR/images/            the images, as recorded (never written by hexcal)
//   DIR/legs.csv           image,L1..L6[,holdout]: the readings at each image
//                          (recorded; never written by hexcal)
//   DIR/camera_poses.csv   camera_from_target per image (hexcal measure columns)
//   DIR/results/           calibrated robot, report
//
// Every write is atomic (core/atomic_file.h). A step replaces only its own
// outputs. Errors name the file and, for legs.csv, the line:
//   legs.csv:4: image 'img_003.png' is not in images/
// docs/session.md describes the folder and the steps.
//
//   SessionConfig config{"inria-left-hand", "camera.yaml", "aprilgrid-6x6"};
//   Status made = InitSession("run1", config);
//   StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs("run1");
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/noise_model.h"
#include "core/pose.h"
#include "core/status.h"

namespace hexcal {

// What measures the platform's pose (docs/session.md, "Point measurements"):
// the camera and its AprilTag board, or an instrument that measures named 3D
// points on the platform (a laser tracker's reflectors, a CMM's probe points).
enum class Instrument { kCamera, kPoints };
const char* InstrumentName(Instrument instrument);  // "camera", "points"

struct SessionConfig {
  std::string robot;   // robot file (relative to the session folder) or preset name
  std::string camera;  // camera file or name, as LoadCamera takes it (camera sessions)
  std::string target;  // target file or name, as LoadTarget takes it (camera sessions)
  Instrument instrument = Instrument::kCamera;
  // Points sessions: the measured points (core/point_file.h, either layout),
  // the reflectors' positions in a frame fixed to the platform (CSV
  // point,x,y,z; empty: estimated from the measured poses), and the σ of each
  // coordinate where the points file gives none (robot unit).
  std::string points;
  std::string reflectors;
  double point_sigma = 0;
  // Set by the registration step (core/registration.h), robot unit; the robot's
  // Euler convention in the file.
  std::optional<Pose> base_from_camera{};
  std::optional<Pose> platform_from_target{};
  NoiseModel noise{};  // pose and reading noise, robot unit and degrees

  bool IsValid(std::string* error) const;
};

// `hexcal session check-noise` keeps its result in the session folder (workflow/noise_check.h).
constexpr const char* kNoiseCheckFile = "noise_check.json";

struct SessionPaths {
  explicit SessionPaths(std::string dir);
  std::string dir, config, plan, images, legs, camera_poses, results;
  std::string noise_check;  // kNoiseCheckFile
};

// Creates DIR (may exist, but must not hold a session.yaml), images/, results/
// and session.yaml.
Status InitSession(const std::string& dir, const SessionConfig& config);

StatusOr<SessionConfig> LoadSessionConfig(const std::string& dir);
// Rewrites session.yaml atomically.
Status SaveSessionConfig(const std::string& dir, const SessionConfig& config);

struct LegsRow {
  std::string image;  // file name inside images/; in a points session, the pose's name in the points file
  LegReadings legs = LegReadings::Zero();
  bool holdout = false;  // kept out of the calibration, used to validate it
  int line = 0;          // line of legs.csv
};

// Reads legs.csv: columns image, L1..L6 and optionally holdout (0 or 1), in any
// order. Every row's image must be in images/, no image twice, and every image
// in images/ must have a row. A points session's legs.csv names its poses in a
// column `pose` instead (the group of the points file), with no images.
StatusOr<std::vector<LegsRow>> LoadSessionLegs(const std::string& dir);

}  // namespace hexcal

// The session folder: one calibration job on disk, shared by the CLI and the GUI.
//
//   DIR/session.yaml       robot, camera, target, registered frames, noise model
//   DIR/plan.csv           the planned poses (hexcal plan --out), optional
//   DIR/images/            the images, as recorded (never written by hexcal)
//   DIR/legs.csv           image,L1..L6[,holdout][,commanded_x..commanded_q3]:
//                          the readings at each image and, for a capture of
//                          the Acquire step, the pose it was commanded to
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

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/noise_model.h"
#include "core/pose.h"
#include "core/status.h"
#include "core/tracker_model.h"

namespace hexcal {

// What measures the platform's pose (docs/session.md, "Point measurements"):
// the camera and its AprilTag board, or an instrument that measures named 3D
// points on the platform (a laser tracker's reflectors, a CMM's probe points).
enum class Instrument { kCamera, kPoints };
const char* InstrumentName(Instrument instrument);  // "camera", "points"
// What one measurement of the instrument is called: "image" or "pose", in
// messages and as the key column of legs.csv.
const char* MeasurementNoun(Instrument instrument);

struct SessionConfig {
  std::string robot;   // robot file (relative to the session folder) or preset name
  std::string camera;  // camera file or name, as LoadCamera takes it (camera sessions)
  std::string target;  // target file or name, as LoadTarget takes it (camera sessions)
  Instrument instrument = Instrument::kCamera;
  // Points sessions: the measured points (core/point_file.h, either layout),
  // the reflectors' positions in a frame fixed to the platform (CSV
  // point,x,y,z; empty: estimated from the measured poses), and the σ of each
  // coordinate where the points file gives none (robot unit).
  std::string points{};
  std::string reflectors{};
  double point_sigma = 0;
  // Points sessions, optional: the tracker's position, σ law and line of
  // sight for the planner (core/tracker_model.h; docs/session.md).
  std::optional<TrackerSettings> tracker{};
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

// legs.csv's optional columns of the pose a capture was commanded to (the
// Acquire step writes them; robot unit and degrees, as plan.csv): they tie an
// image to the planned pose it was taken at by content, not by its name
// (issue 35). Empty cells in a row taken otherwise (loaded, typed).
inline constexpr const char* kCommandedColumns[6] = {"commanded_x",  "commanded_y",  "commanded_z",
                                                     "commanded_q1", "commanded_q2", "commanded_q3"};

struct LegsRow {
  std::string image;  // file name inside images/; in a points session, the pose's name in the points file
  LegReadings legs = LegReadings::Zero();
  bool holdout = false;  // kept out of the calibration, used to validate it
  int line = 0;          // line of legs.csv
  std::optional<Vector6d> commanded{};  // the pose a capture was commanded to, when legs.csv says
};

// Reads legs.csv: columns image, L1..L6 and optionally holdout (0 or 1) and
// the six commanded columns (all six numbers, or all six empty), in any
// order. Every row's image must be in images/, no image twice, and every image
// in images/ must have a row. A points session's legs.csv names its poses in a
// column `pose` instead (the group of the points file), with no images.
StatusOr<std::vector<LegsRow>> LoadSessionLegs(const std::string& dir);

// The commanded pose of legs.csv's row `row` from its six `columns`: none when
// all six cells are empty; an error after `where` ("legs.csv:4: ") when only
// some are, or one is not a number.
StatusOr<std::optional<Vector6d>> CommandedPoseAt(const CsvTable& table, size_t row, const std::array<int, 6>& columns,
                                                  const std::string& where);

}  // namespace hexcal

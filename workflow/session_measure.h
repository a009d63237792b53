// The Measure step of a session folder (docs/session.md, "Measurements and
// what they were measured with"): camera_from_target of each image, kept in
// camera_poses.csv, with camera_poses.json recording the SHA-256 of the
// camera file, the target file and each image a row was measured from. New
// intrinsics or a new target re-measure every row; a replaced image, its own
// row; the rest is reused. `calibrate --session` and the GUI's Measure step
// both go through here.
//
//   StatusOr<SessionMeasurements> m = MeasureSessionImages(dir, images, camera, target, {}, hooks);
//   if (m.ok() && m->remeasure_reason.size()) std::cout << "re-measured: " << m->remeasure_reason;
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/pose.h"
#include "core/session_lock.h"
#include "core/status.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/target.h"

namespace hexcal::workflow {

struct SessionImagePose {
  bool ok = false;
  std::string status;                      // PoseStatusName: "ok", "high_rms", ...
  Pose camera_from_target;                 // target unit
  Matrix6d covariance = Matrix6d::Zero();  // of the pose vector (Euler xyz): target unit², degrees²
};

struct SessionMeasurements {
  std::map<std::string, SessionImagePose> poses;  // by image file name
  int measured = 0;  // images measured by this call
  int reused = 0;    // rows of camera_poses.csv still valid
  // Why rows were measured again, e.g. "the camera changed since measuring";
  // empty when only new images were measured.
  std::string remeasure_reason;
  // With MeasureSessionOptions::keep_observations: the corners of the images
  // this call measured (the calibration from pixels then need not detect them
  // again), by image file name.
  std::map<std::string, BoardObservation> observations;
};

struct MeasureSessionOptions {
  bool all = false;  // measure every image again (the GUI's "Measure all")
  // Hashes of the inputs already computed (HashSessionInputs, session_results.h):
  // used instead of reading the camera, target and images again.
  const std::map<std::string, std::string>* known_hashes = nullptr;
  bool keep_observations = false;  // fill SessionMeasurements::observations
};

// Measures the images (file names in DIR/images/) that have no valid row and
// rewrites camera_poses.csv and camera_poses.json. The caller holds the
// session lock (core/session_lock.h).
StatusOr<SessionMeasurements> MeasureSessionImages(const std::string& session_dir,
                                                   const std::vector<std::string>& images, const Camera& camera,
                                                   const Target& target, const MeasureSessionOptions& options,
                                                   const JobHooks& hooks = {});

// The GUI's Measure step: every image in DIR/images/, with the camera and
// target session.yaml names, holding the session lock.
struct MeasureFolderRequest {
  std::string session;
  bool all = false;  // measure every image again
  LockWait wait = LockWait::kBriefly;
};
StatusOr<SessionMeasurements> MeasureSessionFolder(const MeasureFolderRequest& request, const JobHooks& hooks = {});

// Which of `images` would be measured now, and why ("" when none): for
// `hexcal session status` and the GUI's step list.
struct MeasureState {
  std::vector<std::string> to_measure;
  std::string reason;
};
// `known_hashes`: the session's inputs already hashed (HashSessionInputs), so
// that a status read hashes each image once.
StatusOr<MeasureState> SessionMeasureState(const std::string& session_dir, const std::vector<std::string>& images,
                                           const std::map<std::string, std::string>* known_hashes = nullptr);

}  // namespace hexcal::workflow

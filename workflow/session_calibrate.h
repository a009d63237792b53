// The session steps behind `hexcal calibrate --session DIR` and the GUI's
// Calibrate step (docs/session.md): measure the images not yet in
// camera_poses.csv, register the camera and target frames with the nominal
// robot, calibrate on the rows not held out, validate on the held-out rows,
// publish results/ whole (calibrated.yaml, calibration_measurements.csv,
// report.json, manifest.json: session_results.h) and copy the registered
// frames into session.yaml. Holds the session lock throughout.
//
//   StatusOr<CalibrationReport> report = CalibrateSession({"run1"}, hooks);
//   if (report.ok()) std::cout << FormatCalibrationSummary(*report);
#pragma once

#include <string>

#include "core/job_hooks.h"
#include "core/outlier_screening.h"
#include "core/registration.h"
#include "core/robot.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/status.h"
#include "report/calibration_summary.h"
#include "session/calibration_report.h"
#include "session/session_models.h"
#include "session/session_results.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/session_pixels.h"
#include "workflow/session_points.h"

namespace hexcal::workflow {

struct CalibrateSessionRequest {
  std::string session;  // the session folder
  // Another writer holds the session (core/session_lock.h): stop at once
  // with "session in use by PID n (command)", or wait for it.
  LockWait wait = LockWait::kNo;
  // Every leg reading is screened against the noise model (core/outlier_screening.h);
  // outliers are left out of their leg's fit unless `keep`.
  OutlierScreening outliers = {/*enabled=*/true};
  // Then the calibration from pixels, started from the two-stage one
  // (session_pixels.h); its figures replace the two-stage ones.
  FromPixelsRequest from_pixels = {};
  // A points session's: the calibration from points (session_points.h).
  // Asking explicitly (fall_back false) for the other instrument's fit is bad input.
  FromPointsRequest from_points = {};
};

// Stages reported through hooks.stage: "measure (images)", then "register and
// calibrate" (progress: legs). A cancelled run returns Status::Cancelled and
// writes nothing new to results/.
StatusOr<CalibrationReport> CalibrateSession(const CalibrateSessionRequest& request, const JobHooks& hooks = {});

// The options `calibrate --session` calibrates with: weighted by each image's
// own pose covariance and the model's reading noise; σ at least the a priori
// one (calibration.h, UncertaintyScale); readings screened for outliers
// against that noise (outlier_screening.h).
CalibrationOptions SessionCalibrationOptions(const NoiseModel& noise, const OutlierScreening& outliers);

// Every row of a session with a usable board pose, held out or not, as
// `hexcal study` (study_step.h) draws its subsets from: the images not yet
// measured are measured (under the session lock, as calibrate --session
// does); the frames are registered with the nominal robot on all of them
// (CalibrateFromCameraPoses, the gauge of docs/session.md); each board pose
// is mapped to base_from_platform = X·B·Y⁻¹ with its covariance. Writes
// nothing but camera_poses.csv and its record.
struct MeasuredSession {
  Robot nominal;
  NoiseModel noise;                       // session.yaml's
  std::vector<std::string> images;        // the image of each measurement
  std::vector<Measurement> measurements;  // base frame, robot unit, with the pose covariance
  Registration registration;
  int unusable = 0;  // rows without a usable board pose, left out
  ContentHashes inputs;  // the session's inputs as they were read, under the lock (HashSessionInputs)
};
StatusOr<MeasuredSession> LoadMeasuredSession(const std::string& dir, LockWait wait = LockWait::kNo,
                                              const JobHooks& hooks = {});

}  // namespace hexcal::workflow

// What calibrating a session works on, shared by workflow/session_calibrate.cc,
// workflow/session_rows.cc and workflow/session_joint_fit.cc (internal to
// workflow/): the inputs session.yaml names, the session opened and measured,
// each image's board pose, the rows split into calibration and held-out, and
// the report made from a calibration.
//
//   SplitRows split = SplitSessionRows(in, poses, scale);  // session_calibrate.cc
//   CalibrationReport report = MakeReport(dir, in, split, result);
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/measurements.h"
#include "core/registration.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/validation.h"
#include "session/calibration_report.h"
#include "session/session_results.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/target.h"
#include "workflow/session_measure.h"

namespace hexcal::workflow {

using CameraPose = SessionImagePose;
using CameraPoses = std::map<std::string, SessionImagePose>;

// What session.yaml names, loaded.
struct SessionInputs {
  SessionConfig config;
  std::vector<LegsRow> legs;
  std::string robot_name;
  Robot nominal;
  Camera camera;
  Target target;
  Pose fk_start;  // the centre of the robot's pose box
};

// A session opened under its lock with every image measured: what calibrating
// and the section 8 study both start from.
struct OpenSession {
  SessionLock lock;
  ContentHashes hashes;
  SessionInputs in;
  CameraPoses poses;
  double scale = 1;  // target unit per robot unit
  // The corners of the images measured by this run (`keep_observations`), by file name.
  std::map<std::string, BoardObservation> observations;
};

// The calibration rows (usable, not held out) and the held-out rows.
struct SplitRows {
  CameraCalibrationInput input;
  std::vector<const LegsRow*> calibration_rows;  // the row of each input pose
  std::vector<const LegsRow*> held_out;
  int unusable = 0;
};

// How a row is named in messages: "view_0003.png (legs.csv line 5)".
std::string RowName(const LegsRow& row);
// Every row's readings within a stroke of its leg's stroke (beyond is a typo
// or another unit, which would make FK fail or calibrate another robot); the
// error names the image, its legs.csv line, the leg and the value.
Status CheckRowsNearStroke(const Robot& nominal, const std::vector<LegsRow>& rows);
// The nominal robot's FK from each row's readings converges from `start`
// (what the registration starts from, core/registration.h); the error names
// the image, its legs.csv line and its readings, not "pose 1".
Status CheckNominalFk(const Robot& nominal, const Pose& start, const std::vector<const LegsRow*>& rows);

// Held-out rows: the camera pose mapped into the registered base frame.
std::vector<Measurement> HeldOutMeasurements(const SessionInputs& in, const CameraPoses& poses,
                                             const std::vector<const LegsRow*>& held_out,
                                             const CameraCalibrationResult& result, double scale);
// The FK error the noise model predicts at the held-out poses, or at the
// centre of the pose box without any (expected_error.h).
NoiseExpectation ExpectedNoise(const SessionInputs& in, const std::vector<Measurement>& held_out,
                               const Robot& calibrated);
// FK with the nominal and the calibrated robot on the held-out rows; none without any.
StatusOr<std::optional<ValidationSummary>> ValidateHeldOut(const SessionInputs& in,
                                                           const std::vector<const LegsRow*>& held_out,
                                                           const std::vector<Measurement>& rows,
                                                           const CameraCalibrationResult& result);
// The report of a calibration (results/report.json) without its validation,
// noise and from-pixels parts, which the caller adds.
CalibrationReport MakeReport(const std::string& dir, const SessionInputs& in, const SplitRows& split,
                             const CameraCalibrationResult& result);

}  // namespace hexcal::workflow

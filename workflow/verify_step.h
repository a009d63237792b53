// Checking a machine through the camera (docs/acquisition.md, "Checking the
// machine"): drive the controller to poses, let it settle, grab a frame and
// see where the platform really is, in the session's registered frames:
//
//   base_from_platform = X · camera_from_target · Y⁻¹
//
// (X = base_from_camera, Y = platform_from_target, registered by
// `calibrate --session`; docs/session.md). The error of each pose is the
// distance between commanded and seen positions (robot unit) and the angle of
// the rotation between them (degrees). Before a calibration is loaded into
// the controller this is the controller's own error; after, what is left.
// Nothing is written into the session: the images can be kept elsewhere.
//
//   VerifyRequest request{"run1", "linuxcnc://127.0.0.1:5007", "aravis:Fake", "check.csv"};
//   StatusOr<VerifyResult> checked = VerifyPoses(request, hooks);
//   if (checked.ok()) std::cout << FormatVerifySummary(*checked);
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::workflow {

struct VerifyRequest {
  std::string session;
  std::string controller = "sim";  // URL, devices/controller.h
  std::string camera = "sim";      // URL, devices/frame_source.h
  std::string poses{};             // pose CSV (x,y,z,q1,q2,q3); empty: SESSION/plan.csv
  double settle_seconds = 0.5;     // after each move, before the frame
  int grab_timeout_ms = 5000;
  uint64_t seed = 1;  // of the sim world (sim URLs only)
  // A folder to keep each frame in (check_000k.png); empty: none. Never the
  // session's images/; a check_000k.png there already is refused unless `force`.
  std::string images_out{};
  bool force = false;  // replace check_000k.png files in images_out
};

struct PoseCheck {
  int index = 0;  // row of the pose file, from 0
  Vector6d commanded = Vector6d::Zero();
  std::optional<Vector6d> seen;  // through the camera; none when the board was not measured
  double position_error = 0;     // robot unit
  double orientation_error = 0;  // degrees
  double reprojection_rms_px = 0;
  std::string problem;  // why there is no `seen`, or that --keep-images failed for this frame
};

struct VerifyResult {
  std::string session, controller, camera, length_unit;
  std::vector<PoseCheck> poses;
  double position_rms = 0, position_max = 0;        // over the poses seen, robot unit
  double orientation_rms = 0, orientation_max = 0;  // degrees
  double seconds = 0;

  int Seen() const;
};

// Opens the devices (OpenAcquisitionRig, which writes nothing into the
// session: a `sim` world's truth is checked against the session's, not
// written), then each pose: move, settle, grab, measure the board, compare. A pose that fails (unreachable, no frame,
// the board not measured) is reported and the run goes on. Errors: no frames registered in the session (calibrate
// first), bad poses, devices, a cancel.
StatusOr<VerifyResult> VerifyPoses(const VerifyRequest& request, const JobHooks& hooks = {});

nlohmann::json ToJson(const VerifyResult& result);
std::string FormatVerifySummary(const VerifyResult& result);

}  // namespace hexcal::workflow

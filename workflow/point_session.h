// The Measure step of a points session (docs/session.md, "Point
// measurements"): the platform's pose at each row of legs.csv from the named
// 3D points an instrument measured there (a laser tracker's reflectors),
// fitted to the reflectors' positions (core/point_fit.h). The fits then play
// the camera's part: tracker_from_reflectors is camera_from_target, the
// tracker frame is registered to the base and the reflector frame to the
// platform as the camera's and the target's are (core/registration.h).
//
// Units: the points and reflectors are in the robot's length unit.
//
//   StatusOr<PointPoses> measured = MeasurePointPoses({points, reflectors, sigma}, legs, noise, hooks);
//   measured->poses.at("pose_3");  // ok, camera_from_target, covariance
#pragma once

#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/noise_model.h"
#include "core/point_file.h"
#include "core/session.h"
#include "core/status.h"
#include "workflow/session_measure.h"

namespace hexcal::workflow {

// The files a points session names, resolved to paths.
struct PointFiles {
  std::string points;      // the measured points (either layout of core/point_file.h)
  std::string reflectors;  // CSV point,x,y,z; empty: estimated from the poses (core/reflector_estimate.h)
  double default_sigma = 0;  // σ of a coordinate the points file gives none for
  double noise_factor = 1;   // every fit's σ times this (SessionNoiseFactor)
};

// The points file's sets and the reflectors (as given, or estimated from the
// sets when `files.reflectors` is empty), each point's σ the file's or
// `files.default_sigma` (not yet scaled by `noise_factor`).
struct LoadedPoints {
  PointSets sets;
  std::vector<NamedPoint> reflectors;
  bool estimated = false;
};
StatusOr<LoadedPoints> LoadPoints(const PointFiles& files);

struct PointPoses {
  std::map<std::string, SessionImagePose> poses;  // by legs.csv's pose name
  std::vector<NamedPoint> reflectors;             // as given or estimated
  bool reflectors_estimated = false;
  // The session's noise with its pose half-widths replaced by what the fits'
  // covariances say (the median pose's σ, √3·σ as a uniform half-width,
  // core/noise_model.h): the registration and the verdict's prediction use it.
  NoiseModel noise;
  int left_out = 0;  // rows whose points could not be fitted (named in a warning)
};

// Bad input naming the file and pose: a file that does not load, a row of
// legs.csv whose pose the points file lacks. A pose whose points do not fit
// (fewer than 3, an outlier, an unknown reflector) is left out with a warning
// (hooks.Note) naming it and why.
StatusOr<PointPoses> MeasurePointPoses(const PointFiles& files, const std::vector<LegsRow>& rows,
                                       const NoiseModel& noise, const JobHooks& hooks = {});

// `hexcal measure --points`: every pose of a points file fitted to the
// reflectors, written as tracker_poses.csv (docs/cli.md): pose, x, y, z, q1,
// q2, q3 (the points' unit, degrees, Euler xyz), the six σ, rms (of the point
// residuals), points, status (ok or bad_points) and message. Refuses an
// existing `out` unless `force`.
struct PointMeasureResult {
  int poses = 0, fitted = 0;
  bool reflectors_estimated = false;
};
StatusOr<PointMeasureResult> MeasurePointFile(const PointFiles& files, const std::string& out, bool force);

// The factor a points session's fits' σ are scaled by: the measured/declared
// ratio of DIR/noise_check.json when above 1 (the declared noise was
// optimistic), else 1, and 1 without a check.
StatusOr<double> SessionNoiseFactor(const std::string& session_dir);

// The same files read only to say whether they load and cover legs.csv: for
// `hexcal session status` ("24 point sets, 4 reflectors estimated").
StatusOr<std::string> DescribePointPoses(const PointFiles& files, const std::vector<LegsRow>& rows);

// The files session.yaml names, resolved against the session folder, with the
// σ the points file gives none for and the factor of noise_check.json (1
// without one, or when `with_noise_factor` is false).
StatusOr<PointFiles> SessionPointFiles(const std::string& session_dir, const SessionConfig& config,
                                       bool with_noise_factor = true);

// Each pose's fit as the GUI's Measure step lists it: the points of the pose
// fitted to the reflectors, or why not. Unlike MeasurePointPoses, a pose the
// points file lacks is a row ("no_points"), not an error, so that the list
// shows what else fits.
struct PointPoseFit {
  std::string pose;
  std::string status;   // "ok", "bad_points" (the fit failed: message says why) or "no_points"
  std::string message;  // why not ok; empty when ok
  int points = 0;       // measured points of the pose
  double rms = 0;       // of the point residuals, robot unit (ok only)
};
struct PointPoseReview {
  std::vector<PointPoseFit> poses;  // in the order asked for
  int reflectors = 0;
  bool reflectors_estimated = false;
  int fitted = 0;  // poses whose status is ok
};
// Error: the points file or the reflector file does not load, or the
// reflectors cannot be estimated.
StatusOr<PointPoseReview> ReviewPointPoses(const PointFiles& files, const std::vector<std::string>& poses);

}  // namespace hexcal::workflow

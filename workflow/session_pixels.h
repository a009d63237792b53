// `calibrate --session DIR --from-pixels`: the calibration from pixels
// (vision/pixel_calibration.h) run on a session after its two-stage
// calibration, which gives it the registered frames (the gauge), the start
// values and the screened-out readings (docs/calibration.md, "Calibration
// from pixels").
//
// The images' corners are detected again (camera_poses.csv keeps poses, not
// corners); with estimated intrinsics or target scale, the held-out images'
// board poses are estimated again with them, so that the validation uses the
// camera the calibration found.
//
//   StatusOr<SessionPixelFit> fit = FitSessionFromPixels(setup, two_stage, FromPixelsRequest{true}, hooks);
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/noise_model.h"
#include "core/option_spec.h"
#include "core/outlier_screening.h"
#include "core/registration.h"
#include "core/status.h"
#include "session/pixel_fit_summary.h"
#include "vision/camera.h"
#include "vision/pixel_calibration.h"
#include "vision/target.h"

namespace hexcal::workflow {

// The calibration from pixels is the default: on the demo scenes it is at
// least as accurate as the two-stage one, and removes an error of the focal
// length that the two-stage one cannot (docs/calibration.md).
struct FromPixelsRequest {
  bool enabled = true;           // false: the two-stage calibration alone (--two-stage)
  // When the fit fails (e.g. the focal length is not identifiable from the
  // poses), keep the two-stage calibration with a note; false (--from-pixels
  // given explicitly): the failure is the calibration's.
  bool fall_back = true;
  bool focal = true;             // estimate a common scale of fx and fy
  bool principal_point = false;  // estimate cx, cy
  bool target_scale = false;     // estimate the printed board's scale
};

// The option `estimate` (the flag --estimate): the camera and target
// quantities the calibration from pixels estimates, a list of choices
// "focal", "principal", "scale", or the single word "none".
const OptionSpec<FromPixelsRequest>& PixelEstimatesOption();

// The request of an `estimate` list, read by PixelEstimatesOption; it comes
// back enabled, falling back. Bad input names the option and the choices.
StatusOr<FromPixelsRequest> ParsePixelEstimates(const std::string& list);

// What the fit needs of the session: the images in the order of the
// two-stage calibration's measurements, and the held-out ones.
struct SessionPixelSetup {
  Robot nominal;
  Camera camera;
  Target target;
  double target_to_robot = 1;  // robot unit per target unit
  NoiseModel noise;            // session.yaml's: the readings' σ
  std::vector<std::string> calibration_images, held_out_images;  // paths
  std::vector<LegReadings> calibration_legs;
  // Corners already detected in this run (session_measure.h), by image path:
  // those images are not detected again.
  std::map<std::string, BoardObservation> known_observations;
};

struct SessionPixelFit {
  PixelCalibrationResult fit;
  // camera_from_target of every image (robot unit) from its corners with the
  // fitted camera and target scale; nullopt where the board pose fails.
  std::vector<std::optional<Pose>> calibration_poses, held_out_poses;
};

// With `screening` enabled, the leg readings are screened on the fit from
// pixels itself, as the two-stage fit screens them (core/outlier_screening.h):
// a first fit with a Cauchy loss of 3 σ_L on the readings, then a reading is
// an outlier of leg i when |z| > threshold · max(1, ŝ_i); the final least
// squares fit leaves the outliers out unless `keep`. The two-stage fit's own
// flags are not used: a camera error (a wrong focal length) makes it flag
// correct readings that the fit from pixels explains.
StatusOr<SessionPixelFit> FitSessionFromPixels(const SessionPixelSetup& setup,
                                               const CameraCalibrationResult& two_stage,
                                               const FromPixelsRequest& request, const OutlierScreening& screening,
                                               const JobHooks& hooks = {});

// The summary for report.json, with the two-stage figures to compare.
PixelFitSummary SummarizeSessionPixelFit(const SessionPixelFit& fit, const TwoStageComparison& two_stage);

}  // namespace hexcal::workflow

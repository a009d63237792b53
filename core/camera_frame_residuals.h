// Residuals of a two-stage session calibration in the camera frame, and the
// diagnosis of a bias along the camera's optical axis (docs/calibration.md,
// "Bias along the optical axis"; the paper's section 8 found 1.29 mm).
//
// Image j: the camera measures camera_from_target B_j, so the platform is at
// A'_j = X B_j Y⁻¹ (X = base_from_camera, Y = platform_from_target); the
// calibrated robot's local FK from the image's readings, started at A'_j,
// gives F_j. The residual is where the robot puts the platform minus where
// the camera saw it, in the camera frame (x right, y down, z along the
// optical axis, away from the camera; robot unit):
//   δ_j = R_Xᵀ (p(F_j) − p(A'_j)),
// and the platform's position seen from the camera is u_j = p(X⁻¹ A'_j), its
// depth z_j = u_j.z. Per camera axis a: mean, sample standard deviation,
// standard error and t = mean / (std/√n); the least-squares line
// δ_a ≈ c + k·z_j (depth slope) and δ_a ≈ c + k·u_j[a] (scale slope), each
// with its standard error. The platform's origin, not the target's: the
// target's origin (a board corner, 16 cm off the centre in the demo) moves
// in depth mostly with the platform's tilt, and that part of a depth error
// the calibration absorbs through Y and the platform joints.
//
// Causes. Camera depths (1+ε) times too long (a focal length ε too large)
// give δz ≈ −ε z and no lateral error; a target file whose sizes are (1+s)
// times the real ones gives δ ≈ −s u on all three axes. The calibration
// absorbs part of either (the registration every constant, the 42 parameters
// much of a scale), so what is left of each is simulated on the session's own
// poses (SimulateBiasSignatures) and the x and y scale slopes compared with
// what each cause, of the size that explains k_z, would leave there.
//
//   StatusOr<CameraFrameResiduals> r = ComputeCameraFrameResiduals(
//       result.calibration.robot, result.registration, input.camera_from_target, input.legs,
//       result.registration_left_out);
//   CameraFrameFinding finding = DiagnoseCameraFrameBias(*r);  // finding.text: "" or the clause
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/inverse_kinematics.h"
#include "core/pose.h"
#include "core/registration.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

// Significance: a mean or a slope is significant when |t| (mean / its
// standard error, slope / its standard error) exceeds the Student-t bound of
// the two-sided probability 0.27 % — that of |z| > 3 for a normal variable —
// with n − 1 (mean) or n − 2 (slope) degrees of freedom: 4.3 for a slope over
// 10 images, 3.4 over 24 (SignificanceBound). Residuals of clean simulated
// sessions have the Student-t's spread (median |t| 0.6-0.8).
inline constexpr double kBiasSignificance = 3;  // as a normal deviate
// The same for the two lateral slopes at once: χ² with 2 degrees of freedom
// exceeded with probability 0.27 %.
inline constexpr double kBiasChiSquare2 = 11.83;
// Fewer images than this make no finding: the residuals of 6 n pose
// coordinates, less 42 parameters and 12 frame coordinates, have too few
// degrees of freedom left (kMinRowsToScreen of the outlier screening too).
inline constexpr int kMinImagesForBias = 10;

// The |t| bound above for `dof` degrees of freedom (Cornish-Fisher expansion
// of the Student-t quantile; within 1 % of the exact one from 4 up).
double SignificanceBound(int dof);

struct AxisResiduals {
  double mean = 0, std_dev = 0, standard_error = 0;  // robot unit
  double t = 0;                                      // mean / standard_error
  double depth_slope = 0, depth_slope_se = 0;        // dδ_a/dz, unit-free
  double scale_slope = 0, scale_slope_se = 0;        // dδ_a/du_a, unit-free (for z the depth slope)
};

// The slopes a unit error of one cause leaves in the residuals after the
// calibration: k_z against depth, and the x and y scale slopes. Without any
// absorption: focal length {−1, 0, 0}, target scale {−1, −1, −1}.
struct BiasSignature {
  double depth_slope = 0, x_slope = 0, y_slope = 0;  // per unit of error, unit-free
};
struct BiasSignatures {
  BiasSignature focal_length{-1, 0, 0}, target_scale{-1, -1, -1};
};

struct CameraFrameResiduals {
  int images = 0;                       // images the statistics are over
  int fk_failed = 0;                    // images left out because FK did not converge
  double depth_min = 0, depth_max = 0;  // range of z_j, robot unit
  std::array<AxisResiduals, 3> axes;    // x, y, z of the camera frame
  // Simulated on the session's poses when the residual grows with depth;
  // none: the unabsorbed signatures above are assumed.
  std::optional<BiasSignatures> signatures;
};

// Over the images not in `left_out` (indices, e.g. registration_left_out:
// images holding an excluded outlier reading). camera_from_target in the
// robot unit. Fails with fewer than 3 usable images or when the platform
// does not move along every camera axis (no slope).
StatusOr<CameraFrameResiduals> ComputeCameraFrameResiduals(const Robot& calibrated, const Registration& registration,
                                                           const std::vector<Pose>& camera_from_target,
                                                           const std::vector<LegReadings>& legs,
                                                           const std::vector<int>& left_out = {});

// A cause of bias as what it does to the camera poses: those (robot unit)
// the camera would have given with an error `error` (unit-free) of it.
using CameraPoseError = std::function<StatusOr<std::vector<Pose>>(std::vector<Pose> camera_from_target, double error)>;
struct BiasCauseModels {
  CameraPoseError focal_length, target_scale;
};
// Depths scaled by 1 + error (a focal length error: exact for a pinhole
// camera and a point target; a lens's distortion and a board's extent add
// lateral and rotation errors, session/camera_frame_diagnosis.h models
// those), and whole positions (a target scale error: exact).
BiasCauseModels ScalingBiasModels();

// Calibrates `input` (without the images in `left_out`) again as given, and
// with the camera poses of each cause at an error of 1e-3; the slopes'
// changes per unit of error. Outlier screening and uncertainty are switched
// off: only the estimate matters here.
StatusOr<BiasSignatures> SimulateBiasSignatures(const Robot& nominal, const CameraCalibrationInput& input,
                                                const std::vector<int>& left_out,
                                                const RegistrationOptions& registration_options,
                                                CalibrationOptions calibration_options,
                                                const BiasCauseModels& models = ScalingBiasModels());

enum class BiasCause {
  kNone,          // no bias along the optical axis, or too few images
  kOffset,        // a mean offset that does not grow with depth
  kFocalLength,   // grows with depth; the x and y slopes fit a focal length error
  kTargetScale,   // grows with depth; the x and y slopes fit a target scale error
  kUndetermined,  // grows with depth; both causes fit, or neither alone
};

struct CameraFrameFinding {
  bool optical_axis_bias = false;  // |t_z| or |k_z|/se(k_z) significant (SignificanceBound)
  bool grows_with_depth = false;   // |k_z|/se(k_z) significant
  BiasCause cause = BiasCause::kNone;
  // The error of that cause explaining k_z: ε of the camera's depths, or s of
  // the target's sizes (positive: too long / too large); 0 otherwise.
  double implied_error = 0;
  std::string text;  // e.g. "a bias along the optical axis; points to the focal length (...)"; empty: none
};

// The reasoning of docs/calibration.md, "Bias along the optical axis".
CameraFrameFinding DiagnoseCameraFrameBias(const CameraFrameResiduals& residuals);

}  // namespace hexcal

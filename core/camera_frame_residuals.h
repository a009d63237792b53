// Residuals of a two-stage session calibration in the camera frame, and the
// diagnosis of a bias along the camera's optical axis (docs/calibration.md,
// "Bias along the optical axis"; the paper's section 8 found 1.29 mm).
//
// Image j: the camera measures camera_from_target B_j; the calibrated robot's
// local FK from the image's readings, started at the measured pose
// A'_j = X B_j Y⁻¹, gives F_j. The residual is where the robot puts the
// target minus where the camera saw it, in the camera frame (x right, y down,
// z along the optical axis, away from the camera; robot unit):
//   δ_j = p(X⁻¹ F_j Y) − p(B_j) = R_Xᵀ (p(F_j Y) − p(A'_j Y)).
// Per camera axis a: mean, sample standard deviation, standard error and
// t = mean / (std/√n); the least-squares line δ_a ≈ c + k·z_j against the
// target's depth z_j = p(B_j).z (depth slope), and δ_a ≈ c + k·u_j against the
// axis's own coordinate u_j = p(B_j)[a] (scale slope), each with its standard
// error.
//
// Causes. Camera depths (1+ε) times too long (a focal length ε too large)
// give δz ≈ −ε z and no lateral error; a target file whose sizes are (1+s)
// times the real ones gives δ ≈ −s p(B) on all three axes. The calibration
// absorbs part of either (the registration every constant, the 42 parameters
// much of a scale), so what is left of each is simulated on the session's own
// poses (SimulateBiasSignatures) and the lateral scale slope compared with
// what each cause would leave there.
//
//   StatusOr<CameraFrameResiduals> r = ComputeCameraFrameResiduals(
//       result.calibration.robot, result.registration, input.camera_from_target, input.legs,
//       result.registration_left_out);
//   CameraFrameFinding finding = DiagnoseCameraFrameBias(*r);  // finding.text: "" or the clause
#pragma once

#include <array>
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

// Significance bound of a mean (|t|) and of a slope (|k| / its standard error).
inline constexpr double kBiasSignificance = 3;
// Fewer images than this make no finding: the t-values then scatter too much.
inline constexpr int kMinImagesForBias = 6;

struct AxisResiduals {
  double mean = 0, std_dev = 0, standard_error = 0;  // robot unit
  double t = 0;                                      // mean / standard_error
  double depth_slope = 0, depth_slope_se = 0;        // dδ_a/dz, unit-free
  double scale_slope = 0, scale_slope_se = 0;        // dδ_a/du_a, unit-free (for z the depth slope)
};

// The depth slope k_z and the lateral scale slope (x and y combined) that a
// unit error of one cause leaves in the residuals after the calibration.
// Without absorption: focal length {−1, 0}, target scale {−1, −1}.
struct BiasSignature {
  double depth_slope = 0, lateral_slope = 0;  // per unit of error, unit-free
};
struct BiasSignatures {
  BiasSignature focal_length{-1, 0}, target_scale{-1, -1};
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
// robot unit. Fails with fewer than 3 usable images or when the targets'
// positions do not vary along every camera axis (no slope).
StatusOr<CameraFrameResiduals> ComputeCameraFrameResiduals(const Robot& calibrated, const Registration& registration,
                                                           const std::vector<Pose>& camera_from_target,
                                                           const std::vector<LegReadings>& legs,
                                                           const std::vector<int>& left_out = {});

// The x and y scale slopes as one (inverse-variance weighted), with its standard error.
struct LateralSlope {
  double slope = 0, se = 0;
};
LateralSlope CombinedLateralSlope(const CameraFrameResiduals& residuals);

// Calibrates `input` (without the images in `left_out`) again as given, and
// with every camera depth, then every camera position, scaled by 1 + 1e-3;
// the slopes' changes per unit of error. Outlier screening and uncertainty
// are switched off: only the estimate matters here.
StatusOr<BiasSignatures> SimulateBiasSignatures(const Robot& nominal, const CameraCalibrationInput& input,
                                                const std::vector<int>& left_out,
                                                const RegistrationOptions& registration_options,
                                                CalibrationOptions calibration_options);

enum class BiasCause {
  kNone,          // no bias along the optical axis, or too few images
  kOffset,        // a mean offset that does not grow with depth
  kFocalLength,   // grows with depth; the lateral slope fits a focal length error
  kTargetScale,   // grows with depth; the lateral slope fits a target scale error
  kUndetermined,  // grows with depth; both causes fit, or neither alone
};

struct CameraFrameFinding {
  bool optical_axis_bias = false;  // |t_z| or |k_z|/se(k_z) above kBiasSignificance
  bool grows_with_depth = false;   // |k_z|/se(k_z) above kBiasSignificance
  BiasCause cause = BiasCause::kNone;
  // The error of that cause explaining k_z: ε of the camera's depths, or s of
  // the target's sizes (positive: too long / too large); 0 otherwise.
  double implied_error = 0;
  std::string text;  // e.g. "a bias along the optical axis; points to the focal length (...)"; empty: none
};

// The reasoning of docs/calibration.md, "Bias along the optical axis".
CameraFrameFinding DiagnoseCameraFrameBias(const CameraFrameResiduals& residuals);

}  // namespace hexcal

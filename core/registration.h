// Registration of the camera and target frames to the robot (robot–world
// hand–eye calibration, AX = ZB form), and calibration from camera poses.
//
// A camera fixed to the base watches a target fixed to the platform. Image j
// gives camera_from_target B_j; the leg readings give, through local FK of the
// nominal robot, base_from_platform A_j. Two unknown rigid transforms close
// the loop:
//   A_j · Y = X · B_j,   X = base_from_camera,  Y = platform_from_target.
//
// Estimation (EstimateRegistration):
//  1. Rotations, linear: R_Aj R_Y = R_X R_Bj is, with vec(M N P) = (Pᵀ⊗M) vec(N),
//     [(I⊗R_Aj)  −(R_Bjᵀ⊗I)] [vec R_Y; vec R_X] = 0 for every j; the stacked
//     9N×18 system's least right singular vector, scaled by det^(1/3) and each
//     half projected on SO(3) (nearest rotation by SVD).
//  2. Translations, linear least squares: R_Aj t_Y − t_X = R_X t_Bj − t_Aj.
//  3. Refinement (Ceres, Levenberg–Marquardt) of both transforms on all poses:
//     residual j = [(p(A_j Y) − p(X B_j)) / σ_p ; log(R(X B_j)ᵀ R(A_j Y)) / σ_θ],
//     the platform-side target pose against the camera-side one, in the base
//     frame; X, Y as angle-axis + translation.
//
// Gauge (CalibrateFromCameraPoses): the 42 parameters are only defined up to a
// rigid change of the base frame (a_i → G a_i) and of the platform frame
// (b_i → H b_i), which maps every pose A to G A H⁻¹ and leaves every leg
// length unchanged; X and Y absorb exactly these 12 freedoms. hexcal fixes
// them by registering with the NOMINAL robot once: the base and platform
// frames of the calibrated robot are those in which the nominal robot best
// explains the camera poses (step 3's least squares). The camera poses are
// then mapped into that base frame, A'_j = X B_j Y⁻¹, and the 42 parameters
// identified from (A'_j, L_j) by Calibrate. Re-registering with the calibrated
// robot would not move the frames (the calibrated robot reproduces the A'_j up
// to noise, so X, Y are already its least-squares registration), which is why
// the gauge is fixed by the nominal robot. Against a true robot with frames
// X*, Y*, the estimates are the truth moved by G = X X*⁻¹, H = Y Y*⁻¹
// (ExpressInFrames), small when the nominal robot is close to the true one.
//
//   RegistrationInput input{base_from_platform, camera_from_target};
//   StatusOr<Registration> reg = EstimateRegistration(input, RegistrationOptions{});
//   // reg->base_from_camera, reg->platform_from_target, reg->position_rms, ...
#pragma once

#include <vector>

#include "core/calibration.h"
#include "core/job_hooks.h"
#include "core/measurements.h"
#include "core/noise_model.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"
#include "core/validation.h"

namespace hexcal {

struct RegistrationOptions {
  double position_sigma = 1.0;    // robot unit; weight of the position residuals
  double angle_sigma_deg = 0.05;  // degrees; weight of the rotation residuals
  int max_iterations = 200;       // LM iterations of the refinement
  bool refine = true;             // false: the linear estimate only

  bool IsValid(std::string* error) const;
};

// The refinement weighted by a noise model's position and angle standard
// deviations (what a session calibrates with, docs/session.md).
RegistrationOptions RegistrationOptionsFromNoise(const NoiseModel& noise);

struct Registration {
  Pose base_from_camera;      // X
  Pose platform_from_target;  // Y
  // Closure errors |A_j Y − X B_j| over the poses after the estimate:
  // position in the robot unit, angle in degrees.
  double position_rms = 0, position_max = 0;
  double angle_rms_deg = 0, angle_max_deg = 0;
  int iterations = 0;  // refinement iterations (0 without refinement)
};

// Estimates X and Y from pairs (A_j, B_j), both in the robot length unit.
// Needs at least 3 pairs with non-parallel relative rotations; fails with the
// reason for too few pairs, non-finite input or a degenerate pose set.
StatusOr<Registration> EstimateRegistration(const std::vector<Pose>& base_from_platform,
                                            const std::vector<Pose>& camera_from_target,
                                            const RegistrationOptions& options = {});

// The pose of the platform in the registered base frame: X · B · Y⁻¹ (core/pose.h).
Pose BaseFromPlatform(const Registration& registration, const Pose& camera_from_target);

// The robot with its frames moved: a_i → G a_i (G = new_base_from_old_base),
// b_i → H b_i (H = new_platform_from_old_platform), l_i kept.
Robot ExpressInFrames(const Robot& robot, const Pose& new_base_from_old_base,
                      const Pose& new_platform_from_old_platform);

struct CameraCalibrationInput {
  std::vector<Pose> camera_from_target;  // robot unit
  std::vector<LegReadings> legs;         // the readings at each image
  std::vector<Pose> fk_start;            // start pose of the local FK for each image
  // Optional (empty, or one per image): the covariance of each camera pose as
  // the vector VectorFromPose(camera_from_target, kXYZ), robot unit² and
  // degrees² (vision/board_pose.h gives it). Mapped to the base frame through
  // the registered X and Y (first order), it weights that image in the
  // calibration (Measurement::pose_covariance).
  std::vector<Matrix6d> camera_pose_covariance;
};

struct CameraCalibrationResult {
  Registration registration;              // with the nominal robot: fixes the gauge
  std::vector<Measurement> measurements;  // X B_j Y⁻¹ with the readings
  CalibrationResult calibration;
  // Images left out of the registration and the closure below: those holding
  // a reading excluded as an outlier (calibration_options.outliers), indices.
  std::vector<int> registration_left_out;
  // Closure errors with the calibrated robot (its FK against X B_j Y⁻¹):
  // the RMS over the images in neither list below, and each image's own row
  // (ok false where FK did not converge).
  double calibrated_position_rms = 0, calibrated_angle_rms_deg = 0;
  std::vector<ValidationRow> closure_rows;
  // Images left out of the closure's RMS: registration_left_out and those
  // holding a reading the calibration excluded, ascending.
  std::vector<int> closure_left_out;
};

// The images holding a reading excluded as an outlier, ascending indices.
std::vector<int> ImagesWithExcludedOutliers(const CalibrationResult& calibration);

// Fills the closure fields of `result` from its calibration and measurements
// (the calibrated robot's FK against each measurement's pose). Fails when FK
// converges on none of the images that count.
Status ComputeCalibratedClosure(CameraCalibrationResult* result);

// The covariance of nominal.VectorFromPose(X · B · Y⁻¹) from that of
// VectorFromPose(B, kXYZ) (robot unit², degrees²): J Σ Jᵀ, J by central differences.
Matrix6d MapCameraPoseCovariance(const Robot& nominal, const Registration& registration,
                                 const Pose& camera_from_target, const Matrix6d& covariance);

// Registration with the nominal robot, then Calibrate on the mapped poses.
// With outlier screening (calibration_options.outliers, not kept), images
// holding an excluded reading are then left out of a second registration,
// since their FK pose is wrong too, and the calibration redone in its frames.
// `hooks` go to Calibrate (calibration.h).
StatusOr<CameraCalibrationResult> CalibrateFromCameraPoses(const Robot& nominal, const CameraCalibrationInput& input,
                                                           const RegistrationOptions& registration_options = {},
                                                           const CalibrationOptions& calibration_options = {},
                                                           const JobHooks& hooks = {});

}  // namespace hexcal

// Calibration from points: the 42 kinematic parameters fitted to the points a
// laser tracker measured, not to the poses fitted to them first (issue 38;
// docs/calibration.md, "Calibration from points"). The analogue for a points
// session of the calibration from pixels (vision/pixel_calibration.h).
//
// One least-squares problem (Ceres, Levenberg–Marquardt, the poses eliminated
// by the dense Schur complement) over
//   - the 42 parameters (a_i, b_i, l_i);
//   - the platform pose A_j (base_from_platform) of every pose;
//   - the reflectors' positions r_k in the platform frame (optional, on by
//     default);
// with two kinds of residual:
//   - each measured point: (X⁻¹ · A_j · r_k − m_jk) / σ_jk, 3 per point,
//     σ_jk the point's σ per coordinate (point_calibration_cost.h);
//   - each leg reading: (|A_j b_i − a_i| − (l_i + L_ij)) / σ_L
//     (leg_reading_residual.h), σ_L the reading noise's standard deviation.
//
// The gauge. Base and platform frames have 12 rigid freedoms that no residual
// sees. X = base_from_tracker stays where the registration put it: that fixes
// the base frame (moving X moves every a_i and A_j with it; estimating X
// jointly would be the same freedom again). The platform frame is fixed by the
// reflectors: held at their start values, or, when estimated, moved only
// within the subspace that keeps their centroid and mean orientation at the
// start's (point_calibration_cost.h). So the results are in the frames of the
// two-stage calibration the fit starts from, and 42 + 3K − 6 global unknowns
// remain (42 with the reflectors held).
//
// Uncertainty: the covariance of the global unknowns is the inverse of JᵀJ
// with the pose blocks eliminated (Schur complement), scaled by max(1, s²),
// s² = Σ r² / (m − n) the variance factor, as the calibration from pixels.
// Identifiability: that reduced information matrix scaled to unit diagonal;
// its rank and smallest/largest eigenvalue ratio are reported, and a ratio
// below 1e-12 is refused naming the unknowns of the weakest direction.
//
//   PointCalibrationInput input{nominal, start, X, reflectors_in_platform, poses};
//   StatusOr<PointCalibrationResult> fit = CalibrateFromPoints(input, PointCalibrationOptions{});
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/job_hooks.h"
#include "core/point_fit.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

struct PointCalibrationOptions {
  bool estimate_reflectors = true;  // false: the reflectors stay as given
  double leg_sigma = 0.001;         // standard deviation of a leg reading, robot unit (> 0)
  // > 0: a Cauchy loss of this many σ_L on the leg residuals (the screening
  // pass of the session, as the calibration from pixels'); 0: least squares.
  double leg_cauchy_scale = 0;
  int max_iterations = 100;  // Levenberg–Marquardt iterations
  int num_threads = 0;       // 0: every core

  bool IsValid(std::string* error) const;
};

// One pose: its points, its readings and where the platform starts.
struct PointCalibrationPose {
  std::string name;                 // for messages (legs.csv's pose)
  std::vector<NamedPoint> points;   // tracker frame, robot unit; σ > 0 per coordinate
  LegReadings legs;                 // robot unit
  Pose base_from_platform;          // start value (X B_j Y⁻¹ of the two-stage calibration)
  std::array<bool, kNumLegs> leg_excluded = {};  // readings left out, by leg
};

struct PointCalibrationInput {
  Robot nominal;                       // the parameters' "initial" values in the result
  Robot start;                         // the start of the fit (the two-stage calibration)
  Pose base_from_tracker;              // X, fixed (the base gauge)
  std::vector<NamedPoint> reflectors;  // platform frame: start values, or fixed
  std::vector<PointCalibrationPose> poses;
};

// One point's residual at the fit: predicted − measured, tracker frame.
struct PointResidual {
  int pose = 0;  // index into input.poses
  std::string name;
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();  // robot unit
  double sigma = 0;                                    // of each coordinate
};

struct PointIdentifiability {
  int unknowns = 0;  // global unknowns: 42, + 3K − 6 with the reflectors estimated
  int rank = 0;      // of the scaled reduced information (eigenvalues above 1e-12 of the largest)
  double eigenvalue_ratio = 0;  // its smallest / largest eigenvalue (1/condition number)
  // The unknowns the weakest direction moves most, e.g. "leg 2 bz, reflector R3 x".
  std::string weakest;
};

struct PointCalibrationResult {
  CalibrationResult calibration;       // the 42 parameters with covariance, per leg
  std::vector<NamedPoint> reflectors;  // fitted (or as given), platform frame
  // 3K × 3K, platform frame; rank 3K − 6 (the gauge); zero when held.
  Eigen::MatrixXd reflector_covariance;
  bool reflectors_estimated = false;
  // The largest |correlation| of a reflector coordinate with a parameter.
  double largest_reflector_correlation = 0;
  std::vector<Pose> base_from_platform;  // the fitted pose of every pose
  // Per pose and leg: z = −r at the fit (positive: the reading is longer than
  // the pose implies); NaN where excluded.
  std::vector<LegReadings> leg_z;
  std::vector<PointResidual> point_residuals;
  int points = 0, leg_rows = 0;
  double point_rms = 0;         // RMS of |predicted − measured| over the points, robot unit
  double leg_residual_rms = 0;  // robot unit, over every leg reading used
  double variance_factor = 0;   // s² = Σ r² / (m − n)
  PointIdentifiability identifiability;
  int iterations = 0;
  std::string termination;  // Ceres's, e.g. "CONVERGENCE"
};

constexpr int kMinPointCalibrationPoses = 7;  // as Calibrate: 7 parameters per leg
constexpr double kMinEigenvalueRatio = 1e-12;

// Bad input, named: invalid options, fewer than 7 poses, fewer than 3
// reflectors or reflectors on one line, a reflector named twice, a pose with
// fewer than 3 points, its points on one line, a point not among the
// reflectors or measured twice, a σ not positive, a non-finite value.
// Failed: the data do not determine the unknowns (named: the weakest
// direction), or the solve does not converge. Cancelled: hooks.cancel raised.
StatusOr<PointCalibrationResult> CalibrateFromPoints(const PointCalibrationInput& input,
                                                     const PointCalibrationOptions& options,
                                                     const JobHooks& hooks = {});

}  // namespace hexcal

// The options, input and result of the calibration from points
// (point_calibration.h, which has the model, the gauge and the usage), apart
// from it so that the problem's internals (point_calibration_fit.h) can use
// them without including the function that builds the problem.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/joint_fit_settings.h"
#include "core/point_fit.h"
#include "core/pose.h"
#include "core/robot.h"

namespace hexcal {

struct PointCalibrationOptions : JointFitSettings {
  bool estimate_reflectors = true;  // false: the reflectors stay as given
};

// One pose: its points, its readings and where the platform starts.
struct PointCalibrationPose {
  std::string name;                              // for messages (legs.csv's pose)
  std::vector<NamedPoint> points;                // tracker frame, robot unit; σ > 0 per coordinate
  LegReadings legs;                              // robot unit
  Pose base_from_platform;                       // start value (X B_j Y⁻¹ of the two-stage calibration)
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
  int unknowns = 0;             // global unknowns: 42, + 3K − 6 with the reflectors estimated
  int rank = 0;                 // of the scaled reduced information (eigenvalues above 1e-12 of the largest)
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

}  // namespace hexcal

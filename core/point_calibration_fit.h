// Inside the calibration from points (point_calibration.h): the problem as
// built, and from it the identifiability figures and the result — residuals,
// the covariance of the 42 parameters and the reflectors with the poses
// eliminated (Schur complement of JᵀJ), σ. Internal: includes Ceres.
#pragma once

#include <ceres/ceres.h>

#include <array>
#include <string>
#include <vector>

#include "core/joint_fit_information.h"
#include "core/point_calibration_types.h"

namespace hexcal {

struct PointRow {
  int pose = 0, reflector = 0;
  double sigma = 0;
};

struct PointFitProblem {
  ceres::Problem problem;
  std::array<LegParameters, kNumLegs> legs;
  std::vector<Vector6d> poses;  // [ω, t] of base_from_platform; never resized once the residuals are added
  Eigen::VectorXd reflectors;   // [r_1 … r_K], platform frame
  std::vector<std::string> reflector_names;
  bool estimate_reflectors = false;
  std::vector<ceres::ResidualBlockId> point_rows;
  std::vector<PointRow> point_of_row;
  std::array<std::vector<ceres::ResidualBlockId>, kNumLegs> leg_rows;
  std::array<std::vector<int>, kNumLegs> leg_poses;  // the pose of each of leg_rows
};

// The information of the legs and, when estimated, the reflectors with the
// poses eliminated, at the problem's current values.
JointFitInformation Information(PointFitProblem& fit);

// The rank and eigenvalue ratio of `information` (Information(fit)), and the
// unknowns of its weakest direction.
PointIdentifiability Identifiability(const JointFitInformation& information, PointFitProblem& fit);

// The result without the poses, iterations and termination, from the
// information and identifiability at the solution.
PointCalibrationResult SummarizePointFit(const PointCalibrationInput& input, PointFitProblem& fit,
                                         const PointCalibrationOptions& options,
                                         const JointFitInformation& information,
                                         const PointIdentifiability& identifiability);

}  // namespace hexcal

// The uncertainty of a joint fit's global unknowns — the 42 parameters and
// the camera, target or reflector quantities it estimates — with every
// platform pose eliminated: the Schur complement of JᵀJ over the 6 × 6 pose
// blocks (docs/calibration.md, "Calibration from pixels", "Uncertainty and
// identifiability"). The calibrations from pixels
// (vision/pixel_calibration_covariance.h) and from points
// (core/point_calibration_fit.h) both summarise their solved problem with it.
//
//   JointFitColumns columns;  // the global blocks, then one block per pose
//   columns.blocks = {legs..., extras..., poses...};
//   columns.global_columns = kNumParams + extra_columns;
//   columns.poses = poses;
//   const JointFitInformation information = ReducedInformationAt(&problem, columns);
//   const Eigen::MatrixXd covariance = information.Covariance();
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <vector>

#include "core/calibration_types.h"

namespace hexcal {

// The Jacobian's columns: the global blocks first (global_columns in their
// tangent spaces), then the poses, 6 columns each.
struct JointFitColumns {
  std::vector<double*> blocks;
  int global_columns = 0;
  int poses = 0;
};

struct JointFitInformation {
  Eigen::MatrixXd reduced;  // H_gg − Σ_j H_gj H_jj⁻¹ H_jg, H = JᵀJ
  double cost = 0;          // ½ Σ r² at the solution
  int rows = 0;             // residuals
  int unknowns = 0;         // global columns + 6 per pose

  // s² = 2·cost / (rows − unknowns); 0 without redundancy.
  double VarianceFactor() const;
  // reduced⁻¹ · max(1, s²): a fit worse than its σ widens the uncertainty,
  // a better one does not narrow it.
  Eigen::MatrixXd Covariance() const;
};

JointFitInformation ReducedInformationAt(ceres::Problem* problem, const JointFitColumns& columns);

// The residuals r (in σ) of `rows`, in their order, without the loss
// function: a leg's reading residuals in the fit's screening and figures.
std::vector<double> ResidualsOf(ceres::Problem* problem, const std::vector<ceres::ResidualBlockId>& rows);

// Leg `leg`'s estimate with its 7 × 7 block of `covariance`, σ and the
// square roots of the marginal information's eigenvalues, which stand for
// J's singular values (descending).
void FillLegUncertainty(int leg, const LegParameters& estimate, const Eigen::MatrixXd& covariance,
                        double variance_factor, LegCalibration* out);

}  // namespace hexcal

#include "core/joint_fit_information.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

namespace hexcal {

using Eigen::MatrixXd;
using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

double JointFitInformation::VarianceFactor() const { return rows > unknowns ? 2 * cost / (rows - unknowns) : 0; }

MatrixXd JointFitInformation::Covariance() const {
  return reduced.ldlt().solve(MatrixXd::Identity(reduced.rows(), reduced.cols())) * std::max(1.0, VarianceFactor());
}

JointFitInformation ReducedInformationAt(ceres::Problem* problem, const JointFitColumns& columns) {
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = columns.blocks;
  evaluate.num_threads = 1;
  ceres::CRSMatrix crs;
  JointFitInformation information;
  problem->Evaluate(evaluate, &information.cost, nullptr, nullptr, &crs);
  const SparseRows jacobian(Eigen::Map<const SparseRows>(crs.num_rows, crs.num_cols,
                                                         static_cast<int>(crs.values.size()), crs.rows.data(),
                                                         crs.cols.data(), crs.values.data()));
  information.rows = crs.num_rows;
  const int g = columns.global_columns;
  information.unknowns = g + 6 * columns.poses;
  const Eigen::SparseMatrix<double> h = (jacobian.transpose() * jacobian).pruned();
  information.reduced = MatrixXd(h.topLeftCorner(g, g));
  for (int j = 0; j < columns.poses; ++j) {
    const int c = g + 6 * j;
    const Eigen::Matrix<double, 6, 6> d = MatrixXd(h.block(c, c, 6, 6));
    const MatrixXd b = MatrixXd(h.block(0, c, g, 6));
    information.reduced -= b * d.ldlt().solve(b.transpose());
  }
  return information;
}

std::vector<double> ResidualsOf(ceres::Problem* problem, const std::vector<ceres::ResidualBlockId>& rows) {
  if (rows.empty()) return {};
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.residual_blocks = rows;
  evaluate.apply_loss_function = false;
  evaluate.num_threads = 1;
  std::vector<double> residuals;
  problem->Evaluate(evaluate, nullptr, &residuals, nullptr, nullptr);
  return residuals;
}

void FillLegUncertainty(int leg, const LegParameters& estimate, const MatrixXd& covariance, double variance_factor,
                        LegCalibration* out) {
  out->estimate = estimate;
  out->has_uncertainty = true;
  out->covariance = covariance.block<kParamsPerLeg, kParamsPerLeg>(kParamsPerLeg * leg, kParamsPerLeg * leg);
  out->std_dev = out->covariance.diagonal().cwiseSqrt();
  out->variance_factor = variance_factor;
  const Eigen::VectorXd values = Eigen::SelfAdjointEigenSolver<InfoBlock>(out->covariance.inverse()).eigenvalues();
  for (int k = 0; k < kParamsPerLeg; ++k)
    out->singular_values[k] = std::sqrt(std::max(0.0, values[kParamsPerLeg - 1 - k]));
}

}  // namespace hexcal

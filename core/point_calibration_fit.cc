#include "core/point_calibration_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/point_calibration_cost.h"

namespace hexcal {
namespace {

using Eigen::MatrixXd;
using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The global blocks (legs, then the reflectors when estimated) and the pose
// blocks, in the column order of the Jacobian (the reflectors' tangent space).
struct ColumnLayout {
  std::vector<double*> blocks;
  int global_columns = kNumParams;
  int reflector_columns = 0;
  int poses = 0;
};

ColumnLayout Columns(PointFitProblem& fit) {
  ColumnLayout layout;
  for (LegParameters& leg : fit.legs) layout.blocks.push_back(leg.data());
  if (fit.estimate_reflectors) {
    layout.blocks.push_back(fit.reflectors.data());
    layout.reflector_columns = fit.problem.ParameterBlockTangentSize(fit.reflectors.data());
    layout.global_columns += layout.reflector_columns;
  }
  for (Vector6d& pose : fit.poses) layout.blocks.push_back(pose.data());
  layout.poses = static_cast<int>(fit.poses.size());
  return layout;
}

SparseRows JacobianAt(PointFitProblem& fit, const ColumnLayout& layout, double* cost) {
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.parameter_blocks = layout.blocks;
  evaluate.num_threads = 1;
  ceres::CRSMatrix crs;
  fit.problem.Evaluate(evaluate, cost, nullptr, nullptr, &crs);
  return Eigen::Map<const SparseRows>(crs.num_rows, crs.num_cols, static_cast<int>(crs.values.size()), crs.rows.data(),
                                      crs.cols.data(), crs.values.data());
}

// H_gg − Σ_j H_gj H_jj⁻¹ H_jg, H = JᵀJ: the global unknowns' information
// with every pose eliminated (each pose a 6 × 6 diagonal block).
MatrixXd ReducedInformation(const SparseRows& jacobian, const ColumnLayout& layout) {
  const int g = layout.global_columns;
  const Eigen::SparseMatrix<double> h = (jacobian.transpose() * jacobian).pruned();
  MatrixXd reduced = MatrixXd(h.topLeftCorner(g, g));
  for (int j = 0; j < layout.poses; ++j) {
    const int c = g + 6 * j;
    const Eigen::Matrix<double, 6, 6> d = MatrixXd(h.block(c, c, 6, 6));
    const MatrixXd b = MatrixXd(h.block(0, c, g, 6));
    reduced -= b * d.ldlt().solve(b.transpose());
  }
  return reduced;
}

const Eigen::MatrixXd* ReflectorBasis(PointFitProblem& fit) {
  const auto* gauge = dynamic_cast<const ReflectorGaugeManifold*>(fit.problem.GetManifold(fit.reflectors.data()));
  return gauge != nullptr ? &gauge->basis() : nullptr;
}

// "leg 2 bz", "reflector R3 x", ... for the ambient unknowns.
std::vector<std::string> AmbientNames(const PointFitProblem& fit) {
  std::vector<std::string> names;
  for (int i = 0; i < kNumLegs; ++i)
    for (int k = 0; k < kParamsPerLeg; ++k) names.push_back("leg " + std::to_string(i + 1) + " " + ParameterName(k));
  for (const std::string& name : fit.reflector_names)
    for (const char* axis : {" x", " y", " z"}) names.push_back("reflector " + name + axis);
  return names;
}

// A global direction in the tangent coordinates mapped to the ambient ones.
Eigen::VectorXd Ambient(const Eigen::VectorXd& tangent, const Eigen::MatrixXd* basis) {
  if (basis == nullptr) return tangent.head(kNumParams);
  Eigen::VectorXd ambient(kNumParams + basis->rows());
  ambient << tangent.head(kNumParams), *basis * tangent.tail(basis->cols());
  return ambient;
}

// The (up to) three unknowns a direction moves most.
std::string LargestComponents(const Eigen::VectorXd& direction, const std::vector<std::string>& names) {
  std::vector<int> order(direction.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(direction[a]) > std::abs(direction[b]); });
  std::string text;
  for (int n = 0; n < std::min<int>(3, static_cast<int>(order.size())); ++n) {
    if (n > 0 && std::abs(direction[order[n]]) < 0.2 * std::abs(direction[order[0]])) break;
    text += (text.empty() ? "" : ", ") + names[order[n]];
  }
  return text;
}

PointIdentifiability IdentifiabilityOf(const MatrixXd& information, const Eigen::MatrixXd* basis,
                                       const PointFitProblem& fit) {
  PointIdentifiability out;
  out.unknowns = static_cast<int>(information.rows());
  const Eigen::VectorXd d = information.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const MatrixXd scaled = d.asDiagonal() * information * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixXd> eigen(scaled);
  const Eigen::VectorXd values = eigen.eigenvalues();
  const double largest = values[values.size() - 1];
  for (int k = 0; k < values.size(); ++k) out.rank += values[k] > kMinEigenvalueRatio * largest ? 1 : 0;
  out.eigenvalue_ratio = largest > 0 && values[0] > 0 ? values[0] / largest : 0;
  // The weakest direction in the unknowns' own units, then named.
  const Eigen::VectorXd weakest = d.asDiagonal() * eigen.eigenvectors().col(0);
  out.weakest = LargestComponents(Ambient(weakest, basis), AmbientNames(fit));
  return out;
}

// One leg's reading residuals r (in σ_L), in the order of fit.leg_rows[leg].
std::vector<double> LegResiduals(PointFitProblem& fit, int leg) {
  if (fit.leg_rows[leg].empty()) return {};
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.residual_blocks = fit.leg_rows[leg];
  evaluate.apply_loss_function = false;
  evaluate.num_threads = 1;
  std::vector<double> residuals;
  fit.problem.Evaluate(evaluate, nullptr, &residuals, nullptr, nullptr);
  return residuals;
}

void FillLegs(const PointCalibrationInput& input, PointFitProblem& fit, const MatrixXd& covariance,
              const PointCalibrationOptions& options, double variance_factor, PointCalibrationResult* result) {
  CalibrationResult& calibration = result->calibration;
  ParameterVector estimates;
  double leg_sum = 0;
  result->leg_z.assign(input.poses.size(), LegReadings::Constant(std::nan("")));
  for (int i = 0; i < kNumLegs; ++i) {
    LegCalibration& leg = calibration.legs[i];
    leg.initial = LegParametersOf(input.nominal.legs[i]);
    leg.estimate = fit.legs[i];
    estimates.segment<kParamsPerLeg>(kParamsPerLeg * i) = leg.estimate;
    leg.has_uncertainty = true;
    leg.covariance = covariance.block<kParamsPerLeg, kParamsPerLeg>(kParamsPerLeg * i, kParamsPerLeg * i);
    leg.std_dev = leg.covariance.diagonal().cwiseSqrt();
    leg.variance_factor = variance_factor;
    const std::vector<double> r = LegResiduals(fit, i);
    double sum = 0;
    for (size_t k = 0; k < r.size(); ++k) {
      sum += r[k] * r[k];
      result->leg_z[fit.leg_poses[i][k]][i] = -r[k];
    }
    leg.residual_rms = r.empty() ? 0 : options.leg_sigma * std::sqrt(sum / r.size());
    leg.rows_used = static_cast<int>(r.size());
    leg_sum += sum * options.leg_sigma * options.leg_sigma;
    result->leg_rows += leg.rows_used;
    // The marginal information's square roots stand for J's singular values.
    Eigen::VectorXd values = Eigen::SelfAdjointEigenSolver<InfoBlock>(leg.covariance.inverse()).eigenvalues();
    for (int k = 0; k < kParamsPerLeg; ++k)
      leg.singular_values[k] = std::sqrt(std::max(0.0, values[kParamsPerLeg - 1 - k]));
  }
  calibration.robot = WithParameters(input.start, estimates);
  calibration.num_measurements = static_cast<int>(input.poses.size());
  result->leg_residual_rms = result->leg_rows > 0 ? std::sqrt(leg_sum / result->leg_rows) : 0;
}

void FillReflectors(const PointCalibrationInput& input, const PointFitProblem& fit, const MatrixXd& covariance,
                    const Eigen::MatrixXd* basis, PointCalibrationResult* result) {
  const int count = static_cast<int>(input.reflectors.size());
  result->reflectors_estimated = fit.estimate_reflectors;
  for (int k = 0; k < count; ++k)
    result->reflectors.push_back({input.reflectors[k].name, fit.reflectors.segment<3>(3 * k), 0});
  result->reflector_covariance = MatrixXd::Zero(3 * count, 3 * count);
  if (basis == nullptr) return;
  const int t = static_cast<int>(basis->cols());
  result->reflector_covariance = *basis * covariance.block(kNumParams, kNumParams, t, t) * basis->transpose();
  const MatrixXd cross = *basis * covariance.block(kNumParams, 0, t, kNumParams);  // reflectors × parameters
  for (int a = 0; a < cross.rows(); ++a) {
    for (int b = 0; b < kNumParams; ++b) {
      const double scale = std::sqrt(result->reflector_covariance(a, a) * covariance(b, b));
      if (scale > 0)
        result->largest_reflector_correlation =
            std::max(result->largest_reflector_correlation, std::abs(cross(a, b)) / scale);
    }
  }
  for (int k = 0; k < count; ++k)
    result->reflectors[k].sigma = std::sqrt(result->reflector_covariance.block<3, 3>(3 * k, 3 * k).trace() / 3);
}

void FillPointResiduals(const PointCalibrationInput& input, PointFitProblem& fit, PointCalibrationResult* result) {
  double sum = 0;
  for (size_t n = 0; n < fit.point_rows.size(); ++n) {
    const PointRow& row = fit.point_of_row[n];
    Eigen::Vector3d whitened;
    double cost = 0;
    fit.problem.EvaluateResidualBlock(fit.point_rows[n], false, &cost, whitened.data(), nullptr);
    const Eigen::Vector3d residual = whitened * row.sigma;
    result->point_residuals.push_back({row.pose, input.reflectors[row.reflector].name, residual, row.sigma});
    sum += residual.squaredNorm();
  }
  result->points = static_cast<int>(fit.point_rows.size());
  result->point_rms = result->points > 0 ? std::sqrt(sum / result->points) : 0;
}

}  // namespace

PointIdentifiability Identifiability(PointFitProblem& fit) {
  const ColumnLayout layout = Columns(fit);
  double cost = 0;
  const MatrixXd information = ReducedInformation(JacobianAt(fit, layout, &cost), layout);
  return IdentifiabilityOf(information, fit.estimate_reflectors ? ReflectorBasis(fit) : nullptr, fit);
}

PointCalibrationResult SummarizePointFit(const PointCalibrationInput& input, PointFitProblem& fit,
                                         const PointCalibrationOptions& options,
                                         const PointIdentifiability& identifiability) {
  const ColumnLayout layout = Columns(fit);
  double cost = 0;
  const SparseRows jacobian = JacobianAt(fit, layout, &cost);
  const MatrixXd information = ReducedInformation(jacobian, layout);
  const int rows = static_cast<int>(jacobian.rows());
  const int unknowns = layout.global_columns + 6 * layout.poses;
  PointCalibrationResult result;
  result.identifiability = identifiability;
  result.variance_factor = rows > unknowns ? 2 * cost / (rows - unknowns) : 0;
  const MatrixXd covariance = information.ldlt().solve(MatrixXd::Identity(information.rows(), information.cols())) *
                              std::max(1.0, result.variance_factor);
  FillLegs(input, fit, covariance, options, result.variance_factor, &result);
  FillReflectors(input, fit, covariance, fit.estimate_reflectors ? ReflectorBasis(fit) : nullptr, &result);
  FillPointResiduals(input, fit, &result);
  return result;
}

}  // namespace hexcal

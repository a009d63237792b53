#include "core/point_calibration_fit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/joint_fit_information.h"
#include "core/point_calibration_cost.h"

namespace hexcal {
namespace {

using Eigen::MatrixXd;

// The global blocks (legs, then the reflectors when estimated, in their
// tangent space) and the pose blocks, in the column order of the Jacobian.
JointFitColumns Columns(PointFitProblem& fit) {
  JointFitColumns columns;
  for (LegParameters& leg : fit.legs) columns.blocks.push_back(leg.data());
  columns.global_columns = kNumParams;
  if (fit.estimate_reflectors) {
    columns.blocks.push_back(fit.reflectors.data());
    columns.global_columns += fit.problem.ParameterBlockTangentSize(fit.reflectors.data());
  }
  for (Vector6d& pose : fit.poses) columns.blocks.push_back(pose.data());
  columns.poses = static_cast<int>(fit.poses.size());
  return columns;
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

void FillLegs(const PointCalibrationInput& input, PointFitProblem& fit, const MatrixXd& covariance,
              const PointCalibrationOptions& options, double variance_factor, PointCalibrationResult* result) {
  CalibrationResult& calibration = result->calibration;
  ParameterVector estimates;
  double leg_sum = 0;
  result->leg_z.assign(input.poses.size(), LegReadings::Constant(std::nan("")));
  for (int i = 0; i < kNumLegs; ++i) {
    LegCalibration& leg = calibration.legs[i];
    leg.initial = LegParametersOf(input.nominal.legs[i]);
    FillLegUncertainty(i, fit.legs[i], covariance, variance_factor, &leg);
    estimates.segment<kParamsPerLeg>(kParamsPerLeg * i) = leg.estimate;
    const std::vector<double> r = ResidualsOf(&fit.problem, fit.leg_rows[i]);
    double sum = 0;
    for (size_t k = 0; k < r.size(); ++k) {
      sum += r[k] * r[k];
      result->leg_z[fit.leg_poses[i][k]][i] = -r[k];
    }
    leg.residual_rms = r.empty() ? 0 : options.leg_sigma * std::sqrt(sum / r.size());
    leg.rows_used = static_cast<int>(r.size());
    leg_sum += sum * options.leg_sigma * options.leg_sigma;
    result->leg_rows += leg.rows_used;
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

JointFitInformation Information(PointFitProblem& fit) { return ReducedInformationAt(&fit.problem, Columns(fit)); }

PointIdentifiability Identifiability(const JointFitInformation& information, PointFitProblem& fit) {
  return IdentifiabilityOf(information.reduced, fit.estimate_reflectors ? ReflectorBasis(fit) : nullptr, fit);
}

PointCalibrationResult SummarizePointFit(const PointCalibrationInput& input, PointFitProblem& fit,
                                         const PointCalibrationOptions& options,
                                         const JointFitInformation& information,
                                         const PointIdentifiability& identifiability) {
  PointCalibrationResult result;
  result.identifiability = identifiability;
  result.variance_factor = information.VarianceFactor();
  const MatrixXd covariance = information.Covariance();
  FillLegs(input, fit, covariance, options, result.variance_factor, &result);
  FillReflectors(input, fit, covariance, fit.estimate_reflectors ? ReflectorBasis(fit) : nullptr, &result);
  FillPointResiduals(input, fit, &result);
  return result;
}

}  // namespace hexcal

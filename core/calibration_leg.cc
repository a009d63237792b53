#include "core/ceres_cancel.h"
#include "core/calibration_leg.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "core/calibration_cost.h"
#include "core/csv.h"
#include "core/outlier_screening.h"

namespace hexcal {

std::string LegLabel(int leg) { return "leg " + std::to_string(leg + 1); }

StatusOr<LegData> MakeLegData(const Robot& nominal, int leg, const std::vector<Measurement>& measurements,
                              const std::vector<Pose>& poses, const CalibrationOptions& options) {
  LegData data{poses, {}, {}};
  for (size_t j = 0; j < measurements.size(); ++j) {
    const Measurement& m = measurements[j];
    data.readings.push_back(m.legs[leg]);
    double weight = 1;
    if (options.weighted) {
      weight = m.pose_covariance ? ResidualStdDev(nominal, leg, m.pose, m.legs[leg], options.noise, *m.pose_covariance)
                                 : ResidualStdDev(nominal, leg, m.pose, m.legs[leg], options.noise);
      if (!(weight > 0) || !std::isfinite(weight)) {
        return Status::BadInput("measurement " + std::to_string(j + 1) + ", " + LegLabel(leg) +
                                ": the noise model gives this residual no spread (standard deviation " +
                                std::to_string(weight) + "); weighting needs non-zero noise levels");
      }
    }
    data.weights.push_back(weight);
  }
  return data;
}

LegData LegData::Without(const std::vector<int>& excluded) const {
  LegData kept;
  size_t next = 0;
  for (size_t j = 0; j < size(); ++j) {
    if (next < excluded.size() && excluded[next] == static_cast<int>(j)) {
      ++next;
      continue;
    }
    kept.poses.push_back(poses[j]);
    kept.readings.push_back(readings[j]);
    kept.weights.push_back(weights[j]);
  }
  return kept;
}

namespace {

// The N x 7 Jacobian of the weighted residuals r_ij = F_ij / w_ij at `parameters`.
Eigen::MatrixXd LegJacobian(const LegData& data, const LegParameters& parameters) {
  const Leg leg = LegFromParameters(parameters.data());
  Eigen::MatrixXd jacobian(data.poses.size(), kParamsPerLeg);
  for (size_t j = 0; j < data.poses.size(); ++j) {
    jacobian.row(j) = ImplicitJacobianRow(leg, data.poses[j], data.readings[j]) / data.weights[j];
  }
  return jacobian;
}

LegParameters SingularValues(const Eigen::MatrixXd& jacobian) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(jacobian).singularValues();
}

}  // namespace

Status CheckRank(int leg, const LegData& data, const LegParameters& parameters, const CalibrationOptions& options,
                 const std::string& context) {
  const LegParameters sigma = SingularValues(LegJacobian(data, parameters));
  int rank = 0;
  for (int k = 0; k < kParamsPerLeg; ++k) rank += sigma[k] > options.rank_tolerance * sigma[0];
  if (rank == kParamsPerLeg) return Status::Ok();
  std::ostringstream message;
  message << "degenerate pose set: " << LegLabel(leg) << "'s identification Jacobian has rank " << rank << " of 7 over "
          << data.poses.size() << " measurements" << context
          << " (sigma_min/sigma_max = " << sigma[kParamsPerLeg - 1] / sigma[0] << " < " << options.rank_tolerance
          << "); the poses are repeated or too alike (e.g. one orientation) to identify a, b and l; "
             "measure poses that differ in position and orientation";
  return Status::BadInput(message.str());
}

namespace {

// ρ(s) = b log(1 + s/b) with b = scale². ceres::CauchyLoss evaluates log(1 + s/b),
// which is exactly 0 once s/b < 1e-16: LM then sees a zero cost and stops while
// the parameters are still ~1e-8 off. log1p keeps the small residuals.
class CauchyLoss final : public ceres::LossFunction {
 public:
  explicit CauchyLoss(double scale) : b_(scale * scale), c_(1 / (scale * scale)) {}
  void Evaluate(double s, double rho[3]) const override {
    const double inverse = 1 / (1 + s * c_);
    rho[0] = b_ * std::log1p(s * c_);
    rho[1] = inverse;
    rho[2] = -c_ * inverse * inverse;
  }

 private:
  double b_, c_;
};

std::unique_ptr<ceres::LossFunction> MakeLoss(const CalibrationOptions& options, const LegData& data, double offset) {
  if (options.loss == RobustLoss::kNone) return nullptr;
  // Unweighted, the scale is a leg-length error δ; F ≈ 2ℓδ with ℓ the leg's mean length.
  double scale = options.loss_scale;
  if (!options.weighted) {
    double mean_length = 0;
    for (double reading : data.readings) mean_length += reading + offset;
    scale *= 2 * std::abs(mean_length / data.readings.size());
  }
  if (options.loss == RobustLoss::kHuber) return std::make_unique<ceres::HuberLoss>(scale);
  return std::make_unique<CauchyLoss>(scale);
}

ceres::Solver::Options SolverOptions(const CalibrationOptions& options) {
  ceres::Solver::Options solver;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.parameter_tolerance = options.parameter_tolerance;
  solver.gradient_tolerance = 0;  // the gradient of F² scales with ℓ³: no absolute threshold fits every robot
  solver.num_threads = 1;         // the legs already run in parallel
  solver.logging_type = ceres::SILENT;
  return solver;
}

// Covariance, σ and the identifiability report at the solution.
Status FillUncertainty(int leg, const LegData& data, const CalibrationOptions& options, ceres::Problem* problem,
                       double* parameters, LegCalibration* result) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(LegJacobian(data, result->estimate), Eigen::ComputeThinV);
  result->singular_values = svd.singularValues();
  const double sigma_max = result->singular_values[0];
  for (int k = 0; k < kParamsPerLeg; ++k) {
    const double ratio = result->singular_values[k] / sigma_max;
    if (ratio >= options.weak_direction_ratio) continue;
    WeakDirection weak{ratio, svd.matrixV().col(k)};
    int largest = 0;
    weak.direction.cwiseAbs().maxCoeff(&largest);
    if (weak.direction[largest] < 0) weak.direction = -weak.direction;  // a fixed sign for reports
    result->unidentifiable.push_back(weak);
  }

  const int degrees_of_freedom = static_cast<int>(data.poses.size()) - kParamsPerLeg;
  if (degrees_of_freedom == 0) return Status::Ok();  // an exact fit: no redundancy to estimate the scatter
  // With a robust loss Σ ρ(r²) stands in for the sum of squares.
  result->variance_factor = 2 * result->final_cost / degrees_of_freedom;

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  // DENSE_SVD fails when σ_min/σ_max < √min_reciprocal_condition_number.
  covariance_options.min_reciprocal_condition_number = options.rank_tolerance * options.rank_tolerance;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{parameters, parameters}};
  if (!covariance.Compute(blocks, problem)) {
    return Status::Failed("degenerate pose set: " + LegLabel(leg) +
                          "'s parameters have no finite covariance at the solution (rank-deficient Jacobian)");
  }
  Eigen::Matrix<double, kParamsPerLeg, kParamsPerLeg, Eigen::RowMajor> block;
  covariance.GetCovarianceBlock(parameters, parameters, block.data());
  // A posteriori: scaled by s². At least a priori (weighted, with a trusted
  // noise model): by max(1, s²), so that a scatter below the model's does not
  // shrink σ on the strength of a few degrees of freedom.
  const bool a_priori = options.weighted && options.uncertainty_scale == UncertaintyScale::kAtLeastAPriori;
  result->covariance = (a_priori ? std::max(1.0, result->variance_factor) : result->variance_factor) * block;
  result->std_dev = result->covariance.diagonal().cwiseSqrt();
  result->has_uncertainty = true;
  for (int a = 0; a < kParamsPerLeg; ++a) {
    for (int b = a + 1; b < kParamsPerLeg; ++b) {
      const double correlation = result->covariance(a, b) / (result->std_dev[a] * result->std_dev[b]);
      if (std::abs(correlation) > options.correlation_threshold) result->correlated.push_back({a, b, correlation});
    }
  }
  return Status::Ok();
}

}  // namespace

Status NotConverged(int leg, const LegCalibration& result) {
  std::ostringstream message;
  message << LegLabel(leg) << ": the calibration did not converge (" << result.termination << " after "
          << result.iterations << " iterations: " << result.solver_message << ")";
  return Status::Failed(message.str());
}

bool Converged(const LegCalibration& result) { return result.termination == "CONVERGENCE"; }

StatusOr<LegCalibration> CalibrateLeg(int leg, const LegData& data, const LegParameters& start,
                                      const CalibrationOptions& options, const JobHooks& hooks, bool must_converge) {
  LegCalibration result;
  result.initial = start;
  result.rows_used = static_cast<int>(data.size());
  std::array<double, kParamsPerLeg> parameters;
  Eigen::Map<LegParameters>(parameters.data()) = start;

  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(options, data, start[6]);
  for (size_t j = 0; j < data.poses.size(); ++j) {
    problem.AddResidualBlock(new ImplicitLegCost(data.poses[j], data.readings[j], data.weights[j]), loss.get(),
                             parameters.data());
  }
  ceres::Solver::Options solver = SolverOptions(options);
  CeresCancelCallback cancel_callback(hooks);
  if (hooks.cancel != nullptr) solver.callbacks.push_back(&cancel_callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  if (hooks.Cancelled()) return Status::Cancelled();
  result.termination = ceres::TerminationTypeToString(summary.termination_type);
  result.solver_message = summary.message;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;  // entry 0 is the start
  if (must_converge && !Converged(result)) return NotConverged(leg, result);
  result.estimate = Eigen::Map<const LegParameters>(parameters.data());
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;

  const Leg estimated = LegFromParameters(parameters.data());
  double sum_squares = 0;
  for (size_t j = 0; j < data.poses.size(); ++j) {
    const double error = LegVector(estimated, data.poses[j]).norm() - (data.readings[j] + estimated.offset);
    sum_squares += error * error;
  }
  result.residual_rms = std::sqrt(sum_squares / data.poses.size());

  if (options.compute_uncertainty && Converged(result)) {
    if (Status s = FillUncertainty(leg, data, options, &problem, parameters.data(), &result); !s.ok()) return s;
  }
  return result;
}

namespace {

// z_j = −r_j and (L + l) − |v| of every row at `parameters` (outlier_screening.h).
void RowResiduals(const LegData& data, const LegParameters& parameters, std::vector<double>* z,
                  std::vector<double>* lengths) {
  const Leg leg = LegFromParameters(parameters.data());
  for (size_t j = 0; j < data.size(); ++j) {
    z->push_back(-ImplicitResidual(leg, data.poses[j], data.readings[j]) / data.weights[j]);
    lengths->push_back(data.readings[j] + leg.offset - LegVector(leg, data.poses[j]).norm());
  }
}

std::vector<double> ZOf(const LegData& data, const LegParameters& parameters) {
  std::vector<double> z, lengths;
  RowResiduals(data, parameters, &z, &lengths);
  return z;
}

// The Cauchy fit of the screening at scale 3 σ, from two starts: the nominal
// parameters and the least-squares estimate. A far-off row can bend the
// least-squares fit into another basin of the robust cost (seen on INRIA
// with poses of a small box: 1 cm moved every other row by 60 σ), and a
// nominal robot far from the truth could start in a wrong one too: the lower
// robust cost wins. When the scatter ŝ there exceeds the model's, once more
// at 3 ŝ so that the screening fit keeps its efficiency. The fits need not
// converge: they only lead to the estimate z is read at.
StatusOr<LegParameters> RobustEstimate(int leg, const LegData& data, const LegParameters& nominal,
                                       const LegParameters& least_squares, const CalibrationOptions& options,
                                       const JobHooks& hooks) {
  CalibrationOptions robust = options;
  robust.loss = RobustLoss::kCauchy;
  robust.loss_scale = kScreeningCauchyScale;
  robust.compute_uncertainty = false;
  std::optional<LegCalibration> best;
  for (const LegParameters& start : {nominal, least_squares}) {
    StatusOr<LegCalibration> fit = CalibrateLeg(leg, data, start, robust, hooks, /*must_converge=*/false);
    if (!fit.ok()) return fit.status();
    if (!best || fit->final_cost < best->final_cost) best = std::move(*fit);
  }
  const double scatter = RobustScatter(ZOf(data, best->estimate), kParamsPerLeg);
  if (scatter <= 1) return best->estimate;
  robust.loss_scale = kScreeningCauchyScale * scatter;
  StatusOr<LegCalibration> settled = CalibrateLeg(leg, data, best->estimate, robust, hooks, /*must_converge=*/false);
  if (!settled.ok()) return settled.status();
  return settled->estimate;
}

}  // namespace

StatusOr<LegCalibration> CalibrateLegScreened(int leg, const LegData& data, const LegParameters& nominal,
                                              const CalibrationOptions& options, const JobHooks& hooks) {
  // Only a start when rows are flagged and excluded: it need not converge then.
  StatusOr<LegCalibration> fit = CalibrateLeg(leg, data, nominal, options, hooks, /*must_converge=*/false);
  if (!fit.ok()) return fit;
  if (static_cast<int>(data.size()) < kMinRowsToScreen) return Converged(*fit) ? fit : NotConverged(leg, *fit);
  StatusOr<LegParameters> robust = RobustEstimate(leg, data, nominal, fit->estimate, options, hooks);
  if (!robust.ok()) return robust.status();
  std::vector<double> z, lengths;
  RowResiduals(data, *robust, &z, &lengths);
  const std::vector<int> flagged = FlagOutliers(z, kParamsPerLeg, options.outliers.threshold);
  const bool exclude = !options.outliers.keep;
  if ((flagged.empty() || !exclude) && !Converged(*fit)) {
    std::string kept;
    for (int j : flagged)
      kept += (kept.empty() ? "" : ", ") + std::to_string(j + 1) + " (z = " + FormatNumber(z[j]) + ")";
    const Status failed = NotConverged(leg, *fit);
    return kept.empty() ? failed : Status::Failed(failed.message() + "; outliers kept in its fit: measurement " + kept);
  }
  if (flagged.empty()) return fit;

  std::vector<RowOutlier> outliers;
  for (int j : flagged) outliers.push_back({j, lengths[j], z[j], exclude});
  if (exclude) {
    const LegData kept = data.Without(flagged);
    const std::string context = " left after excluding " + std::to_string(flagged.size()) + " outlier(s)";
    if (kept.size() < static_cast<size_t>(kParamsPerLeg)) {
      return Status::Failed(LegLabel(leg) + ": " + std::to_string(kept.size()) + " measurements" + context +
                            ", fewer than its 7 parameters; check the readings or keep the outliers");
    }
    if (Status s = CheckRank(leg, kept, nominal, options, context); !s.ok()) return s;
    fit = CalibrateLeg(leg, kept, nominal, options, hooks);
    if (!fit.ok()) return fit;
  }
  fit->outliers = std::move(outliers);
  return fit;
}

}  // namespace hexcal

#include "core/calibration.h"

#include <Eigen/SVD>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/calibration_cost.h"
#include "core/csv.h"
#include "core/parallel.h"
#include "core/reading_units.h"

namespace hexcal {
namespace {

// One leg's least-squares problem: the measured poses (shared by the six
// legs), that leg's readings and the weight w_ij of each residual (1 unweighted).
struct LegData {
  const std::vector<Pose>& poses;
  std::vector<double> readings;
  std::vector<double> weights;
};

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
        return Status::Error("measurement " + std::to_string(j + 1) + ", " + LegLabel(leg) +
                             ": the noise model gives this residual no spread (standard deviation " +
                             std::to_string(weight) + "); weighting needs non-zero noise levels");
      }
    }
    data.weights.push_back(weight);
  }
  return data;
}

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

Status CheckRank(int leg, const LegData& data, const LegParameters& nominal, const CalibrationOptions& options) {
  const LegParameters sigma = SingularValues(LegJacobian(data, nominal));
  int rank = 0;
  for (int k = 0; k < kParamsPerLeg; ++k) rank += sigma[k] > options.rank_tolerance * sigma[0];
  if (rank == kParamsPerLeg) return Status::Ok();
  std::ostringstream message;
  message << "degenerate pose set: " << LegLabel(leg) << "'s identification Jacobian has rank " << rank << " of 7 over "
          << data.poses.size() << " measurements (sigma_min/sigma_max = " << sigma[kParamsPerLeg - 1] / sigma[0]
          << " < " << options.rank_tolerance
          << "); the poses are repeated or too alike (e.g. one orientation) to identify a, b and l; "
             "measure poses that differ in position and orientation";
  return Status::Error(message.str());
}

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

class CancelCallback final : public ceres::IterationCallback {
 public:
  explicit CancelCallback(const JobHooks& hooks) : hooks_(hooks) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return hooks_.Cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const JobHooks& hooks_;
};

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
    return Status::Error("degenerate pose set: " + LegLabel(leg) +
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

StatusOr<LegCalibration> CalibrateLeg(int leg, const LegData& data, const LegParameters& nominal,
                                      const CalibrationOptions& options, const JobHooks& hooks) {
  LegCalibration result;
  result.initial = nominal;
  std::array<double, kParamsPerLeg> parameters;
  Eigen::Map<LegParameters>(parameters.data()) = nominal;

  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(options, data, nominal[6]);
  for (size_t j = 0; j < data.poses.size(); ++j) {
    problem.AddResidualBlock(new ImplicitLegCost(data.poses[j], data.readings[j], data.weights[j]), loss.get(),
                             parameters.data());
  }
  ceres::Solver::Options solver = SolverOptions(options);
  CancelCallback cancel_callback(hooks);
  if (hooks.cancel != nullptr) solver.callbacks.push_back(&cancel_callback);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  if (hooks.Cancelled()) return Status::Cancelled();
  result.termination = ceres::TerminationTypeToString(summary.termination_type);
  result.solver_message = summary.message;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;  // entry 0 is the start
  if (summary.termination_type != ceres::CONVERGENCE) {
    std::ostringstream message;
    message << LegLabel(leg) << ": the calibration did not converge (" << result.termination << " after "
            << result.iterations << " iterations: " << summary.message << ")";
    return Status::Error(message.str());
  }
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

  if (options.compute_uncertainty) {
    if (Status s = FillUncertainty(leg, data, options, &problem, parameters.data(), &result); !s.ok()) return s;
  }
  return result;
}

}  // namespace

std::optional<RobustLoss> ParseRobustLoss(const std::string& text) {
  if (text == "none") return RobustLoss::kNone;
  if (text == "huber") return RobustLoss::kHuber;
  if (text == "cauchy") return RobustLoss::kCauchy;
  return std::nullopt;
}

const char* RobustLossName(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "?";
}

const char* ParameterName(int k) {
  static const char* names[kParamsPerLeg] = {"ax", "ay", "az", "bx", "by", "bz", "l"};
  assert(k >= 0 && k < kParamsPerLeg);
  return names[k];
}

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    *error = message;
    return false;
  };
  if (!std::isfinite(loss_scale) || loss_scale <= 0) return fail("loss scale must be positive");
  if (max_iterations < 1) return fail("max_iterations must be at least 1");
  if (!(function_tolerance > 0) || !(parameter_tolerance > 0)) return fail("solver tolerances must be positive");
  if (!(rank_tolerance > 0 && rank_tolerance < 1)) return fail("rank_tolerance must be in (0, 1)");
  if (!(weak_direction_ratio >= 0 && weak_direction_ratio < 1)) return fail("weak_direction_ratio must be in [0, 1)");
  if (!(correlation_threshold > 0 && correlation_threshold <= 1)) {
    return fail("correlation_threshold must be in (0, 1]");
  }
  if (num_threads < 0) return fail("num_threads must be >= 0 (0 = every core)");
  if (weighted) {
    if (!noise.IsValid(error)) return false;
    if (noise.position == 0 && noise.angle_deg == 0 && noise.leg == 0) {
      return fail("weighting needs a noise model with at least one non-zero level");
    }
  }
  return true;
}

ParameterVector CalibrationResult::Estimates() const {
  ParameterVector p;
  for (int i = 0; i < kNumLegs; ++i) p.segment<kParamsPerLeg>(kParamsPerLeg * i) = legs[i].estimate;
  return p;
}

ParameterVector CalibrationResult::StdDevs() const {
  ParameterVector p;
  for (int i = 0; i < kNumLegs; ++i) p.segment<kParamsPerLeg>(kParamsPerLeg * i) = legs[i].std_dev;
  return p;
}

namespace {

// Readings far outside the stroke are not sensor noise but, most often, a file
// in another length unit than the robot's (mm readings for a cm robot are ten
// times too long): calibrating them would give parameters of another robot.
// "Far" is more than one stroke length beyond either end.
Status CheckReadingsInStroke(const Robot& nominal, const std::vector<Measurement>& measurements) {
  std::vector<LegReadings> readings;
  for (const Measurement& m : measurements) readings.push_back(m.legs);
  if (Status s = CheckReadingsUnit(nominal, readings, "measurement"); !s.ok()) return s;
  for (size_t j = 0; j < measurements.size(); ++j) {
    for (int i = 0; i < kNumLegs; ++i) {
      const Leg& leg = nominal.legs[i];
      const double span = leg.stroke_max - leg.stroke_min;
      const double reading = measurements[j].legs[i];
      if (reading >= leg.stroke_min - span && reading <= leg.stroke_max + span) continue;
      const char* unit = LengthUnitName(nominal.length_unit);
      return Status::Error("measurement " + std::to_string(j + 1) + ": L" + std::to_string(i + 1) + " = " +
                           FormatNumber(reading) + " is far outside the stroke [" + FormatNumber(leg.stroke_min) +
                           ", " + FormatNumber(leg.stroke_max) + "] " + unit + " of robot '" + nominal.name +
                           "'; are the readings in " + unit + "?");
    }
  }
  return Status::Ok();
}

}  // namespace

Status CheckCalibrationInput(const Robot& nominal, const std::vector<Measurement>& measurements,
                             const CalibrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("calibration options: " + error);
  if (!ParametersOf(nominal).allFinite()) {
    return Status::Error("robot '" + nominal.name + "': kinematic parameters are not finite");
  }
  if (measurements.size() < static_cast<size_t>(kParamsPerLeg)) {
    return Status::Error("calibration needs at least 7 measurements (7 parameters per leg), got " +
                         std::to_string(measurements.size()));
  }
  for (size_t j = 0; j < measurements.size(); ++j) {
    if (!measurements[j].pose.allFinite() || !measurements[j].legs.allFinite()) {
      return Status::Error("measurement " + std::to_string(j + 1) + ": pose or leg readings are not finite");
    }
  }
  return CheckReadingsInStroke(nominal, measurements);
}

StatusOr<CalibrationResult> Calibrate(const Robot& nominal, const std::vector<Measurement>& measurements,
                                      const CalibrationOptions& options, const JobHooks& hooks) {
  if (Status s = CheckCalibrationInput(nominal, measurements, options); !s.ok()) return s;
  std::vector<Pose> poses;
  poses.reserve(measurements.size());
  for (const Measurement& m : measurements) poses.push_back(nominal.PoseFromVector(m.pose));
  std::vector<LegData> data;
  for (int i = 0; i < kNumLegs; ++i) {
    StatusOr<LegData> leg = MakeLegData(nominal, i, measurements, poses, options);
    if (!leg.ok()) return leg.status();
    if (Status s = CheckRank(i, *leg, LegParametersOf(nominal.legs[i]), options); !s.ok()) return s;
    data.push_back(std::move(*leg));
  }
  if (hooks.Cancelled()) return Status::Cancelled();

  std::vector<std::optional<StatusOr<LegCalibration>>> legs(kNumLegs);
  const bool finished = ParallelFor(
      kNumLegs, options.num_threads,
      [&](int i, int) { legs[i] = CalibrateLeg(i, data[i], LegParametersOf(nominal.legs[i]), options, hooks); }, hooks);
  if (!finished) return Status::Cancelled();

  CalibrationResult result;
  result.num_measurements = static_cast<int>(measurements.size());
  for (int i = 0; i < kNumLegs; ++i) {
    if (legs[i]->status().cancelled()) return legs[i]->status();
  }
  for (int i = 0; i < kNumLegs; ++i) {
    if (!legs[i]->ok()) return legs[i]->status();
    result.legs[i] = std::move(legs[i]->value());
  }
  result.robot = WithParameters(nominal, result.Estimates());
  return result;
}

}  // namespace hexcal

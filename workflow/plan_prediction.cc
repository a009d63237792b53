#include "workflow/plan_prediction.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <optional>

#include "core/candidates.h"
#include "core/identification.h"
#include "core/inverse_kinematics.h"

namespace hexcal::workflow {
namespace {

constexpr double kMeanAbsOverSigma = 0.7978845608028654;  // √(2/π)

// Each pose's own covariance, when it has one (PlanningModel::PoseCovariance).
using PoseCovarianceAt = std::function<std::optional<Matrix6d>(const Vector6d&)>;

// C_i of every leg (see the header); false if a leg's information is singular.
bool ParameterCovariances(const Robot& robot, const std::vector<Vector6d>& poses, const NoiseModel& noise,
                          const PoseCovarianceAt& pose_covariance, bool weighted,
                          std::array<InfoBlock, kNumLegs>* covariances) {
  std::array<InfoBlock, kNumLegs> information, scatter;
  for (int i = 0; i < kNumLegs; ++i) information[i].setZero(), scatter[i].setZero();
  for (const Vector6d& v : poses) {
    const MeasuredPose measured = MeasuredPoseOf(robot, v);  // once for the six legs
    const LegReadings readings = InverseKinematics(robot, measured.pose);  // the nominal model's
    const std::optional<Matrix6d> own = pose_covariance ? pose_covariance(v) : std::nullopt;
    for (int i = 0; i < kNumLegs; ++i) {
      const JacobianRow r = NominalJacobianRow(robot.legs[i], measured.pose);
      const double sd = own ? ResidualStdDev(robot.legs[i], measured, readings[i], noise, *own)
                            : ResidualStdDev(robot.legs[i], measured, readings[i], noise);
      const InfoBlock outer = r.transpose() * r;
      information[i] += weighted ? InfoBlock(outer / (sd * sd)) : outer;
      scatter[i] += sd * sd * outer;
    }
  }
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::LLT<InfoBlock> llt(information[i]);
    if (llt.info() != Eigen::Success) return false;
    const InfoBlock inverse = llt.solve(InfoBlock::Identity());
    (*covariances)[i] = weighted ? inverse : InfoBlock(inverse * scatter[i] * inverse);
  }
  return true;
}

// Squared expectations at one pose of the FK error the parameters cause.
ExpectedPoseError SquaredParameterPoseError(const Robot& robot, const Vector6d& v,
                                            const std::array<InfoBlock, kNumLegs>& covariances) {
  const MeasuredPose measured = MeasuredPoseOf(robot, v);
  const LegReadings readings = InverseKinematics(robot, measured.pose);
  Matrix6d g;
  Vector6d leg_variance;
  for (int i = 0; i < kNumLegs; ++i) {
    g.row(i) = ResidualMeasurementGradient(robot.legs[i], measured, readings[i]).head<6>().transpose();
    const JacobianRow r = NominalJacobianRow(robot.legs[i], measured.pose);
    leg_variance[i] = r * covariances[i] * r.transpose();
  }
  const Eigen::FullPivLU<Matrix6d> lu(g);
  if (!lu.isInvertible()) return {};
  const Matrix6d g_inverse = lu.inverse();
  const Matrix6d covariance = g_inverse * leg_variance.asDiagonal() * g_inverse.transpose();
  return {covariance.topLeftCorner<3, 3>().trace(), RadToDeg(RadToDeg(covariance.bottomRightCorner<3, 3>().trace()))};
}

PlanPrediction Predict(const Robot& robot, const std::vector<Vector6d>& poses, const NoiseModel& noise,
                       const PoseCovarianceAt& pose_covariance, bool weighted,
                       const std::vector<Vector6d>& validation) {
  PlanPrediction prediction;
  std::array<InfoBlock, kNumLegs> covariances;
  if (poses.size() < static_cast<size_t>(kParamsPerLeg) ||
      !ParameterCovariances(robot, poses, noise, pose_covariance, weighted, &covariances)) {
    return prediction;
  }
  for (const InfoBlock& c : covariances) {
    for (int k = 0; k < kParamsPerLeg; ++k) prediction.sigma.push_back(std::sqrt(std::max(c(k, k), 0.0)));
  }
  for (double s : prediction.sigma) {
    prediction.mean_sigma += s / kNumParams;
    prediction.max_sigma = std::max(prediction.max_sigma, s);
  }
  prediction.mean_error = kMeanAbsOverSigma * prediction.mean_sigma;
  ExpectedPoseError sum;
  std::vector<Pose> validation_poses;
  for (const Vector6d& v : validation) {
    const ExpectedPoseError squared = SquaredParameterPoseError(robot, v, covariances);
    sum.position_rms += squared.position_rms;
    sum.orientation_rms_deg += squared.orientation_rms_deg;
    validation_poses.push_back(robot.PoseFromVector(v));
  }
  if (!validation.empty()) {
    const double n = static_cast<double>(validation.size());
    prediction.from_parameters = {std::sqrt(sum.position_rms / n), std::sqrt(sum.orientation_rms_deg / n)};
    const ExpectedPoseError noise_only = ExpectedFkError(robot, validation_poses, noise);
    prediction.heldout = {std::hypot(prediction.from_parameters.position_rms, noise_only.position_rms),
                          std::hypot(prediction.from_parameters.orientation_rms_deg, noise_only.orientation_rms_deg)};
  }
  prediction.valid = true;
  return prediction;
}

}  // namespace

PlanPrediction PredictPlanError(const Robot& robot, const std::vector<Vector6d>& poses, const NoiseModel& noise,
                                bool weighted, const std::vector<Vector6d>& validation) {
  return Predict(robot, poses, noise, {}, weighted, validation);
}

PlanPrediction PredictPlanError(const PlanningModel& model, const std::vector<Vector6d>& poses,
                                const NoiseModel& noise, bool weighted, const std::vector<Vector6d>& validation) {
  return Predict(model.robot, poses, noise, [&model](const Vector6d& v) { return model.PoseCovariance(v); },
                 weighted, validation);
}

std::vector<Vector6d> ValidationPoses(const Robot& robot) {
  CandidateOptions options;
  options.count = 200;
  options.seed = 20050601;  // fixed: every plan of a robot is checked on the same poses
  StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
  return set.ok() ? set->poses : std::vector<Vector6d>{};
}

nlohmann::json NoiseModelJson(const NoiseModel& noise) {
  nlohmann::json json;
  for (const OptionSpec<NoiseModel>& spec : NoiseModelOptions()) json[spec.key] = spec.get_number(noise);
  return json;
}

nlohmann::json ToJson(const PlanPrediction& p, const NoiseModel& noise, bool weighted) {
  const nlohmann::json noise_json = NoiseModelJson(noise);
  if (!p.valid) return {{"valid", false}, {"noise", noise_json}, {"weighted", weighted}};
  return {{"valid", true},
          {"mean_sigma", p.mean_sigma},
          {"max_sigma", p.max_sigma},
          {"mean_error", p.mean_error},
          {"parameter_position_rms", p.from_parameters.position_rms},
          {"parameter_orientation_rms_deg", p.from_parameters.orientation_rms_deg},
          {"heldout_position_rms", p.heldout.position_rms},
          {"heldout_orientation_rms_deg", p.heldout.orientation_rms_deg},
          {"weighted", weighted},
          {"noise", noise_json}};
}

}  // namespace hexcal::workflow

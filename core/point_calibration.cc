#include "core/point_calibration.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>

#include "core/ceres_cancel.h"
#include "core/leg_reading_residual.h"
#include "core/point_calibration_cost.h"
#include "core/point_calibration_fit.h"

namespace hexcal {
namespace {

Status Bad(const std::string& message) { return Status::BadInput("calibration from points: " + message); }

// The second singular value of the centred points over the first: 0 on a line.
bool OnOneLine(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p / static_cast<double>(points.size());
  Eigen::MatrixXd centred(points.size(), 3);
  for (size_t k = 0; k < points.size(); ++k) centred.row(k) = (points[k] - centroid).transpose();
  const Eigen::Vector3d values = Eigen::JacobiSVD<Eigen::MatrixXd>(centred).singularValues();
  return !(values[1] > 1e-6 * values[0]);
}

std::string Names(const std::vector<NamedPoint>& points) {
  std::string text;
  for (const NamedPoint& p : points) text += (text.empty() ? "" : ", ") + p.name;
  return text;
}

Status CheckReflectors(const std::vector<NamedPoint>& reflectors) {
  if (reflectors.size() < 3)
    return Bad(std::to_string(reflectors.size()) + " reflectors; at least 3 not on one line are needed");
  std::set<std::string> names;
  std::vector<Eigen::Vector3d> positions;
  for (const NamedPoint& r : reflectors) {
    if (!names.insert(r.name).second) return Bad("reflector '" + r.name + "' is named twice");
    if (!r.position.allFinite()) return Bad("reflector '" + r.name + "' has a non-finite coordinate");
    positions.push_back(r.position);
  }
  if (OnOneLine(positions))
    return Bad("the reflectors " + Names(reflectors) +
               " lie on one line: the platform's rotation about it is not determined (put a reflector off the line)");
  return Status::Ok();
}

Status CheckPose(const PointCalibrationPose& pose, const std::map<std::string, int>& reflector_index) {
  const std::string which = "pose '" + pose.name + "'";
  if (pose.points.size() < 3)
    return Bad(which + ": " + std::to_string(pose.points.size()) + " points; a pose needs 3 or more reflectors");
  std::set<std::string> seen;
  std::vector<Eigen::Vector3d> positions;
  for (const NamedPoint& p : pose.points) {
    if (reflector_index.count(p.name) == 0) return Bad(which + ": point '" + p.name + "' is not among the reflectors");
    if (!seen.insert(p.name).second) return Bad(which + ": point '" + p.name + "' is measured twice");
    if (!(p.sigma > 0) || !std::isfinite(p.sigma) || !std::isfinite(1 / (p.sigma * p.sigma)))
      return Bad(which + ": point '" + p.name + "' has no positive σ");
    if (!p.position.allFinite()) return Bad(which + ": point '" + p.name + "' has a non-finite coordinate");
    positions.push_back(p.position);
  }
  if (OnOneLine(positions))
    return Bad(which + ": its points " + Names(pose.points) + " lie on one line (the rotation about it is free)");
  if (!pose.legs.allFinite() || !pose.base_from_platform.position.allFinite() ||
      !pose.base_from_platform.rotation.allFinite())
    return Bad(which + " has a non-finite reading or start pose");
  return Status::Ok();
}

Status CheckInput(const PointCalibrationInput& input, const PointCalibrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Bad(error);
  if (static_cast<int>(input.poses.size()) < kMinPointCalibrationPoses)
    return Bad(std::to_string(input.poses.size()) + " poses; at least " + std::to_string(kMinPointCalibrationPoses) +
               " are needed (7 parameters per leg)");
  if (Status s = CheckReflectors(input.reflectors); !s.ok()) return s;
  std::map<std::string, int> index;
  for (size_t k = 0; k < input.reflectors.size(); ++k) index[input.reflectors[k].name] = static_cast<int>(k);
  for (const PointCalibrationPose& pose : input.poses)
    if (Status s = CheckPose(pose, index); !s.ok()) return s;
  return Status::Ok();
}

void AddResiduals(const PointCalibrationInput& input, const PointCalibrationOptions& options,
                  const std::map<std::string, int>& index, PointFitProblem* fit) {
  const int count = static_cast<int>(input.reflectors.size());
  for (int j = 0; j < static_cast<int>(input.poses.size()); ++j) {
    const PointCalibrationPose& pose = input.poses[j];
    for (const NamedPoint& p : pose.points) {
      const int k = index.at(p.name);
      fit->point_rows.push_back(
          fit->problem.AddResidualBlock(new PointResidualCost(input.base_from_tracker, p.position, p.sigma, k, count),
                                        nullptr, fit->poses[j].data(), fit->reflectors.data()));
      fit->point_of_row.push_back({j, k, p.sigma});
    }
    for (int i = 0; i < kNumLegs; ++i) {
      if (pose.leg_excluded[i]) continue;
      auto* cost = new LegReadingResidual{pose.legs[i], options.leg_sigma};
      ceres::LossFunction* loss =
          options.leg_cauchy_scale > 0 ? new ceres::CauchyLoss(options.leg_cauchy_scale) : nullptr;
      fit->leg_rows[i].push_back(
          fit->problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LegReadingResidual, 1, 7, 6>(cost), loss,
                                        fit->legs[i].data(), fit->poses[j].data()));
      fit->leg_poses[i].push_back(j);
    }
  }
}

ceres::Solver::Options SolverOptions(const PointCalibrationOptions& options, PointFitProblem* fit) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;  // the poses eliminated, the rest is small
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (Vector6d& pose : fit->poses) ordering->AddElementToGroup(pose.data(), 0);
  for (LegParameters& leg : fit->legs) ordering->AddElementToGroup(leg.data(), 1);
  ordering->AddElementToGroup(fit->reflectors.data(), 1);
  solver.linear_solver_ordering = ordering;
  SetJointFitLimits(options.max_iterations, options.num_threads, &solver);
  return solver;
}

Status Unidentifiable(const PointIdentifiability& identifiability) {
  return Status::Failed(
      "calibration from points: the data do not determine every unknown (the information matrix has "
      "rank " +
      std::to_string(identifiability.rank) + " of " + std::to_string(identifiability.unknowns) +
      "; its weakest direction moves " + identifiability.weakest + "): add poses that move every leg over its stroke" +
      std::string(identifiability.weakest.find("reflector") != std::string::npos ? ", or keep the reflectors as given"
                                                                                 : ""));
}

}  // namespace

StatusOr<PointCalibrationResult> CalibrateFromPoints(const PointCalibrationInput& input,
                                                     const PointCalibrationOptions& options, const JobHooks& hooks) {
  if (Status s = CheckInput(input, options); !s.ok()) return s;
  std::map<std::string, int> index;
  for (size_t k = 0; k < input.reflectors.size(); ++k) index[input.reflectors[k].name] = static_cast<int>(k);
  auto fit = std::make_unique<PointFitProblem>();
  for (int i = 0; i < kNumLegs; ++i) fit->legs[i] = LegParametersOf(input.start.legs[i]);
  for (const PointCalibrationPose& pose : input.poses) fit->poses.push_back(PoseBlock(pose.base_from_platform));
  fit->reflectors.resize(3 * input.reflectors.size());
  for (size_t k = 0; k < input.reflectors.size(); ++k) fit->reflectors.segment<3>(3 * k) = input.reflectors[k].position;
  fit->estimate_reflectors = options.estimate_reflectors;
  for (const NamedPoint& r : input.reflectors) fit->reflector_names.push_back(r.name);
  AddResiduals(input, options, index, fit.get());
  if (options.estimate_reflectors) {
    auto gauge = std::make_unique<ReflectorGaugeManifold>(fit->reflectors);
    if (!gauge->valid()) return Bad("the reflectors " + Names(input.reflectors) + " lie nearly on one line");
    fit->problem.SetManifold(fit->reflectors.data(), gauge.release());
  } else {
    fit->problem.SetParameterBlockConstant(fit->reflectors.data());
  }
  // Refused before the solve when the start already shows it.
  const PointIdentifiability before = Identifiability(Information(*fit), *fit);
  if (before.eigenvalue_ratio < kMinEigenvalueRatio) return Unidentifiable(before);

  ceres::Solver::Options solver = SolverOptions(options, fit.get());
  CeresCancelCallback cancel(hooks);
  if (hooks.cancel != nullptr) solver.callbacks.push_back(&cancel);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &fit->problem, &summary);
  if (hooks.Cancelled()) return Status::Cancelled("calibration from points: cancelled");
  if (summary.termination_type != ceres::CONVERGENCE)
    return Status::Failed("calibration from points: the solve did not converge (" + summary.message + ")");
  const JointFitInformation information = Information(*fit);  // once, for the check and the result
  const PointIdentifiability after = Identifiability(information, *fit);
  if (after.eigenvalue_ratio < kMinEigenvalueRatio) return Unidentifiable(after);
  PointCalibrationResult result = SummarizePointFit(input, *fit, options, information, after);
  for (const Vector6d& block : fit->poses) result.base_from_platform.push_back(PoseOfBlock(block));
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.termination = ceres::TerminationTypeToString(summary.termination_type);
  return result;
}

}  // namespace hexcal

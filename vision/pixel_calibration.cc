#include "vision/pixel_calibration.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <atomic>
#include <cmath>
#include <memory>

#include "core/ceres_cancel.h"
#include "core/registration.h"
#include "vision/pixel_calibration_cost.h"
#include "vision/pixel_calibration_covariance.h"

namespace hexcal {
namespace {

constexpr int kMinImages = 7;  // as Calibrate: 7 parameters per leg

Status CheckInput(const PixelCalibrationInput& input, const PixelCalibrationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput("calibration from pixels: " + error);
  if (static_cast<int>(input.images.size()) < kMinImages) {
    return Status::BadInput("calibration from pixels: " + std::to_string(input.images.size()) +
                            " images with corners; at least 7 are needed");
  }
  if (!(input.target_to_robot > 0) || !std::isfinite(input.target_to_robot)) {
    return Status::BadInput("calibration from pixels: the target-to-robot unit factor must be positive");
  }
  for (size_t j = 0; j < input.images.size(); ++j) {
    const PixelImage& image = input.images[j];
    if (image.observation.image_points.empty())
      return Status::BadInput("calibration from pixels: image " + std::to_string(j) + " has no corners");
    if (!image.legs.allFinite() || !image.base_from_platform.position.allFinite())
      return Status::BadInput("calibration from pixels: image " + std::to_string(j) + " has a non-finite value");
  }
  return input.camera.Validate();
}

// W with Wᵀ W = C⁻¹ (C = L Lᵀ, W = L⁻¹); a zero C (corners AprilTag placed) is σ² I.
Eigen::Matrix<double, 8, 8> Whitening(const Eigen::Matrix<double, 8, 8>& covariance, double sigma_px) {
  using Matrix8d = Eigen::Matrix<double, 8, 8>;
  Matrix8d c = covariance;
  if (c.isZero(0)) c = Matrix8d::Identity() * sigma_px * sigma_px;
  Eigen::LLT<Matrix8d> llt(c);
  if (llt.info() != Eigen::Success) return Matrix8d::Identity() / sigma_px;
  return llt.matrixL().solve(Matrix8d::Identity());
}

// The unknowns of the problem, in the blocks Ceres changes in place.
struct PixelUnknowns {
  std::array<LegParameters, kNumLegs> legs;
  std::vector<Vector6d> poses;
  double focal = 1;
  Eigen::Vector2d principal = Eigen::Vector2d::Zero();
  double scale = 1;
};

PixelUnknowns StartValues(const PixelCalibrationInput& input) {
  PixelUnknowns unknowns;
  for (int i = 0; i < kNumLegs; ++i) unknowns.legs[i] = LegParametersOf(input.start.legs[i]);
  for (const PixelImage& image : input.images) unknowns.poses.push_back(PoseBlock(image.base_from_platform));
  unknowns.principal = {input.camera.cx, input.camera.cy};
  return unknowns;
}

void AddTagResiduals(const PixelCalibrationInput& input, const PixelCalibrationOptions& options, int j,
                     PixelUnknowns* unknowns, ceres::Problem* problem, PixelFit* fit) {
  const BoardObservation& seen = input.images[j].observation;
  const Pose camera_from_base = Inverse(input.base_from_camera);
  for (size_t t = 0; t < seen.tag_ids.size(); ++t) {
    auto* cost = new TagCornersResidual;
    cost->image = j;
    cost->tag_id = seen.tag_ids[t];
    cost->camera = &input.camera;
    for (int c = 0; c < 4; ++c) {
      cost->corners[c] = seen.target_points[4 * t + c] * input.target_to_robot;
      cost->observed.segment<2>(2 * c) = seen.image_points[4 * t + c];
    }
    cost->whitening = Whitening(seen.corner_covariances[t], options.corner_sigma_px);
    cost->camera_from_base_rotation = camera_from_base.rotation;
    cost->camera_from_base_translation = camera_from_base.position;
    cost->platform_from_target = input.platform_from_target;
    fit->tags.push_back(*cost);
    problem->AddResidualBlock(new ceres::AutoDiffCostFunction<TagCornersResidual, 8, 6, 1, 2, 1>(cost), nullptr,
                              unknowns->poses[j].data(), &unknowns->focal, unknowns->principal.data(),
                              &unknowns->scale);
  }
}

void AddLegResiduals(const PixelCalibrationInput& input, const PixelCalibrationOptions& options, int j,
                     PixelUnknowns* unknowns, ceres::Problem* problem, PixelFit* fit) {
  for (int i = 0; i < kNumLegs; ++i) {
    if (input.images[j].leg_excluded[i]) continue;
    auto* cost = new LegReadingResidual{input.images[j].legs[i], options.leg_sigma};
    ceres::LossFunction* loss =
        options.leg_cauchy_scale > 0 ? new ceres::CauchyLoss(options.leg_cauchy_scale) : nullptr;
    fit->leg_rows[i].push_back(
        problem->AddResidualBlock(new ceres::AutoDiffCostFunction<LegReadingResidual, 1, 7, 6>(cost), loss,
                                  unknowns->legs[i].data(), unknowns->poses[j].data()));
    fit->leg_images[i].push_back(j);
  }
}

void FixUnestimated(const PixelCalibrationOptions& options, PixelUnknowns* unknowns, ceres::Problem* problem) {
  if (!options.estimate_focal) problem->SetParameterBlockConstant(&unknowns->focal);
  if (!options.estimate_principal_point) problem->SetParameterBlockConstant(unknowns->principal.data());
  if (!options.estimate_target_scale) problem->SetParameterBlockConstant(&unknowns->scale);
}

ceres::Solver::Options SolverOptions(const PixelCalibrationOptions& options, PixelUnknowns* unknowns) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;  // the poses eliminated, the rest is small
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (Vector6d& pose : unknowns->poses) ordering->AddElementToGroup(pose.data(), 0);
  for (LegParameters& leg : unknowns->legs) ordering->AddElementToGroup(leg.data(), 1);
  ordering->AddElementToGroup(&unknowns->focal, 1);
  ordering->AddElementToGroup(unknowns->principal.data(), 1);
  ordering->AddElementToGroup(&unknowns->scale, 1);
  solver.linear_solver_ordering = ordering;
  SetJointFitLimits(options.max_iterations, options.num_threads, &solver);
  return solver;
}

}  // namespace

StatusOr<PixelCalibrationResult> CalibrateFromPixels(const PixelCalibrationInput& input,
                                                     const PixelCalibrationOptions& options,
                                                     const JobHooks& hooks) {
  if (Status s = CheckInput(input, options); !s.ok()) return s;
  PixelUnknowns unknowns = StartValues(input);
  ceres::Problem problem;
  PixelFit fit;
  for (int j = 0; j < static_cast<int>(input.images.size()); ++j) {
    AddTagResiduals(input, options, j, &unknowns, &problem, &fit);
    AddLegResiduals(input, options, j, &unknowns, &problem, &fit);
  }
  FixUnestimated(options, &unknowns, &problem);
  ceres::Solver::Options solver = SolverOptions(options, &unknowns);
  CeresCancelCallback cancel(hooks);
  if (hooks.cancel != nullptr) solver.callbacks.push_back(&cancel);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (hooks.Cancelled()) return Status::Cancelled("calibration from pixels: cancelled");
  if (summary.termination_type != ceres::CONVERGENCE) {
    return Status::Failed("calibration from pixels: the solve did not converge (" + summary.message + ")");
  }
  fit.problem = &problem;
  fit.legs = &unknowns.legs;
  fit.poses = &unknowns.poses;
  fit.estimated = {{"focal", &unknowns.focal, 1, options.estimate_focal},
                   {"principal", unknowns.principal.data(), 2, options.estimate_principal_point},
                   {"target_scale", &unknowns.scale, 1, options.estimate_target_scale}};
  StatusOr<PixelCalibrationResult> result = SummarizePixelFit(input, fit, options);
  if (!result.ok()) return result.status();
  for (const Vector6d& block : unknowns.poses) result->base_from_platform.push_back(PoseOfBlock(block));
  result->iterations = static_cast<int>(summary.iterations.size()) - 1;
  result->termination = ceres::TerminationTypeToString(summary.termination_type);
  for (LegCalibration& leg : result->calibration.legs) {
    leg.iterations = result->iterations;
    leg.termination = result->termination;
    leg.initial_cost = summary.initial_cost;
    leg.final_cost = summary.final_cost;
  }
  return result;
}

}  // namespace hexcal

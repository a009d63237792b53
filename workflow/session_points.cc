#include "workflow/session_points.h"

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/csv.h"
#include "core/point_fit.h"
#include "workflow/screened_joint_fit.h"

namespace hexcal::workflow {
namespace {

// The sets of the named poses, each point's σ scaled by the session's factor.
StatusOr<std::vector<std::vector<NamedPoint>>> PointsOf(const LoadedPoints& loaded, const PointFiles& files,
                                                        const std::vector<std::string>& poses) {
  std::map<std::string, const PointSet*> by_name;
  for (const PointSet& set : loaded.sets) by_name[set.pose] = &set;
  std::vector<std::vector<NamedPoint>> points;
  for (const std::string& pose : poses) {
    const auto found = by_name.find(pose);
    if (found == by_name.end())
      return Status::Failed(files.points + ": pose '" + pose + "' has no points (the file changed while calibrating?)");
    std::vector<NamedPoint> scaled = found->second->points;
    for (NamedPoint& p : scaled) p.sigma *= files.noise_factor;
    points.push_back(std::move(scaled));
  }
  return points;
}

PointCalibrationInput FitInput(const SessionPointSetup& setup, const CameraCalibrationResult& two_stage,
                               const LoadedPoints& loaded, const std::vector<std::vector<NamedPoint>>& points) {
  PointCalibrationInput input{
      setup.nominal, two_stage.calibration.robot, two_stage.registration.base_from_camera, {}, {}};
  for (const NamedPoint& r : loaded.reflectors)
    input.reflectors.push_back({r.name, two_stage.registration.platform_from_target * r.position, 0});
  for (size_t j = 0; j < points.size(); ++j) {
    PointCalibrationPose pose;
    pose.name = setup.calibration_poses[j];
    pose.points = points[j];
    pose.legs = setup.calibration_legs[j];
    pose.base_from_platform = setup.nominal.PoseFromVector(two_stage.measurements[j].pose);
    input.poses.push_back(pose);
  }
  return input;
}

// The shape's scale: s = √(Σ|r̂_k − ĉ|² / Σ|r_k − c|²), and its σ from the
// reflectors' covariance, ds = Σ (r̂_k − ĉ)ᵀ dr̂_k / (s Σ|r_k − c|²).
void ShapeScale(const std::vector<NamedPoint>& given, const PointCalibrationResult& fit, SessionPointFit* out) {
  const int count = static_cast<int>(given.size());
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), c_hat = Eigen::Vector3d::Zero();
  for (int k = 0; k < count; ++k) {
    c += given[k].position / count;
    c_hat += fit.reflectors[k].position / count;
  }
  double given_sum = 0, fitted_sum = 0;
  for (int k = 0; k < count; ++k) {
    given_sum += (given[k].position - c).squaredNorm();
    fitted_sum += (fit.reflectors[k].position - c_hat).squaredNorm();
  }
  out->scale = std::sqrt(fitted_sum / given_sum);
  Eigen::VectorXd gradient(3 * count);
  for (int k = 0; k < count; ++k)
    gradient.segment<3>(3 * k) = (fit.reflectors[k].position - c_hat) / (out->scale * given_sum);
  out->scale_sigma = std::sqrt(std::max(0.0, gradient.dot(fit.reflector_covariance * gradient)));
}

// The fitted reflectors back in the reflector frame, Y⁻¹ r̂_k, with their σ.
void ReflectorsInTheirFrame(const LoadedPoints& loaded, const Pose& platform_from_reflectors,
                            const PointCalibrationResult& fit, SessionPointFit* out) {
  const Pose reflectors_from_platform = Inverse(platform_from_reflectors);
  const Eigen::Matrix3d& r = reflectors_from_platform.rotation;
  std::vector<NamedPoint> given_in_platform;
  for (size_t k = 0; k < loaded.reflectors.size(); ++k) {
    out->given.push_back(loaded.reflectors[k]);
    out->fitted.push_back({fit.reflectors[k].name, reflectors_from_platform * fit.reflectors[k].position, 0});
    const Eigen::Matrix3d covariance = r * fit.reflector_covariance.block<3, 3>(3 * k, 3 * k) * r.transpose();
    out->fitted_sigma.push_back(covariance.diagonal().cwiseMax(0).cwiseSqrt());
    given_in_platform.push_back(
        {loaded.reflectors[k].name, platform_from_reflectors * loaded.reflectors[k].position, 0});
  }
  ShapeScale(given_in_platform, fit, out);
}

// Every pose's tracker_from_reflectors with the fitted reflectors.
std::vector<std::optional<Pose>> PosesWith(const std::vector<NamedPoint>& reflectors,
                                           const std::vector<std::vector<NamedPoint>>& points) {
  std::vector<std::optional<Pose>> poses;
  for (const std::vector<NamedPoint>& set : points) {
    StatusOr<PointFit> fit = FitPointPose(reflectors, set);
    poses.push_back(fit.ok() ? std::optional<Pose>(fit->pose) : std::nullopt);
  }
  return poses;
}

}  // namespace

StatusOr<SessionPointFit> FitSessionFromPoints(const SessionPointSetup& setup, const CameraCalibrationResult& two_stage,
                                               const FromPointsRequest& request, const OutlierScreening& screening,
                                               const JobHooks& hooks) {
  hooks.Stage("calibrate from points");
  StatusOr<LoadedPoints> loaded = LoadPoints(setup.files);
  if (!loaded.ok()) return loaded.status();
  StatusOr<std::vector<std::vector<NamedPoint>>> points = PointsOf(*loaded, setup.files, setup.calibration_poses);
  if (!points.ok()) return points.status();
  StatusOr<std::vector<std::vector<NamedPoint>>> held_out = PointsOf(*loaded, setup.files, setup.held_out_poses);
  if (!held_out.ok()) return held_out.status();
  PointCalibrationOptions options;
  options.estimate_reflectors = request.estimate_reflectors;
  options.leg_sigma = setup.noise.LegStdDev();
  StatusOr<PointCalibrationResult> fit =
      ScreenedJointFit(FitInput(setup, two_stage, *loaded, *points), options, screening,
                       &CalibrateFromPoints, &PointCalibrationInput::poses, hooks);
  if (!fit.ok()) return fit.status();
  SessionPointFit result;
  result.from_file = !loaded->estimated;
  ReflectorsInTheirFrame(*loaded, two_stage.registration.platform_from_target, *fit, &result);
  result.fit = std::move(*fit);
  result.calibration_poses = PosesWith(result.fitted, *points);
  result.held_out_poses = PosesWith(result.fitted, *held_out);
  return result;
}

PointFitSummary SummarizeSessionPointFit(const SessionPointFit& session, const TwoStageComparison& two_stage) {
  const PointCalibrationResult& fit = session.fit;
  PointFitSummary summary;
  summary.poses = static_cast<int>(fit.base_from_platform.size());
  summary.points = fit.points;
  summary.leg_rows = fit.leg_rows;
  summary.point_rms = fit.point_rms;
  summary.leg_residual_rms = fit.leg_residual_rms;
  summary.variance_factor = fit.variance_factor;
  summary.iterations = fit.iterations;
  summary.reflectors_estimated = fit.reflectors_estimated;
  summary.reflectors_from_file = session.from_file;
  for (size_t k = 0; k < session.given.size(); ++k) {
    summary.reflectors.push_back(
        {session.given[k].name, session.given[k].position, session.fitted[k].position, session.fitted_sigma[k]});
  }
  summary.reflector_scale = session.scale;
  summary.reflector_scale_sigma = session.scale_sigma;
  summary.largest_reflector_correlation = fit.largest_reflector_correlation;
  summary.unknowns = fit.identifiability.unknowns;
  summary.rank = fit.identifiability.rank;
  summary.eigenvalue_ratio = fit.identifiability.eigenvalue_ratio;
  summary.two_stage = two_stage;
  summary.mean_parameter_sigma = fit.calibration.StdDevs().mean();
  return summary;
}

Status SaveFittedReflectors(const std::string& path, const SessionPointFit& fit) {
  std::vector<std::vector<std::string>> rows;
  for (size_t k = 0; k < fit.fitted.size(); ++k) {
    std::vector<std::string> row = {fit.fitted[k].name};
    for (int a = 0; a < 3; ++a) row.push_back(FormatNumber(fit.fitted[k].position[a]));
    for (int a = 0; a < 3; ++a) row.push_back(FormatNumber(fit.fitted_sigma[k][a]));
    rows.push_back(row);
  }
  return WriteCsv(path, {"point", "x", "y", "z", "sigma_x", "sigma_y", "sigma_z"}, rows);
}

Status SavePointResiduals(const std::string& path, const SessionPointFit& fit,
                          const std::vector<std::string>& pose_names) {
  std::vector<std::vector<std::string>> rows;
  for (const PointResidual& r : fit.fit.point_residuals) {
    const std::string pose = r.pose < static_cast<int>(pose_names.size()) ? pose_names[r.pose] : std::to_string(r.pose);
    rows.push_back({pose, r.name, FormatNumber(r.residual.x()), FormatNumber(r.residual.y()),
                    FormatNumber(r.residual.z()), FormatNumber(r.sigma)});
  }
  return WriteCsv(path, {"pose", "point", "dx", "dy", "dz", "sigma"}, rows);
}

}  // namespace hexcal::workflow

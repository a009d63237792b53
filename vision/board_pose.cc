#include "vision/board_pose.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <optional>

#include "core/csv.h"

namespace hexcal {
namespace {

// Corners AprilTag placed itself (no edge fit) are taken as independent with
// this standard deviation; the variance factor rescales it with the residuals.
constexpr double kUnrefinedCornerSigmaPx = 0.1;

Pose Perturbed(const Pose& pose, const Eigen::Matrix<double, 6, 1>& step) {
  Pose perturbed;
  perturbed.rotation = RotationExp(step.head<3>()) * pose.rotation;
  perturbed.position = pose.position + step.tail<3>();
  return perturbed;
}

// The weighted least-squares problem: residuals whitened tag by tag with the
// corners' covariance, r_w = L⁻¹ r where C = L Lᵀ.
class PoseProblem {
 public:
  PoseProblem(const Camera& camera, const BoardObservation& observation) : camera_(camera), observation_(observation) {
    // One covariance per tag, or none (then every corner weighs the same).
    assert(observation.corner_covariances.empty() ||
           observation.corner_covariances.size() == observation.tag_ids.size());
    for (const Eigen::Matrix<double, 8, 8>& covariance : observation.corner_covariances) {
      const bool known = !covariance.isZero(0);
      const Eigen::Matrix<double, 8, 8> c =
          known ? covariance
                : Eigen::Matrix<double, 8, 8>(kUnrefinedCornerSigmaPx * kUnrefinedCornerSigmaPx *
                                              Eigen::Matrix<double, 8, 8>::Identity());
      const Eigen::LLT<Eigen::Matrix<double, 8, 8>> llt(c);
      whiten_.push_back(
          llt.info() == Eigen::Success
              ? Eigen::Matrix<double, 8, 8>(llt.matrixL().solve(Eigen::Matrix<double, 8, 8>::Identity()))
              : Eigen::Matrix<double, 8, 8>(Eigen::Matrix<double, 8, 8>::Identity() / kUnrefinedCornerSigmaPx));
    }
  }

  Eigen::VectorXd Residuals(const Pose& pose) const {
    Eigen::VectorXd r = ReprojectionResiduals(camera_, observation_, pose);
    for (size_t t = 0; t < whiten_.size(); ++t) {
      const Eigen::Index at = static_cast<Eigen::Index>(8 * t);
      r.segment<8>(at) = whiten_[t] * r.segment<8>(at);
    }
    return r;
  }

  // d residuals / d (δ, ε) by central differences.
  Eigen::MatrixXd Jacobian(const Pose& pose) const {
    const double scale = std::max(1.0, pose.position.norm());
    Eigen::MatrixXd jacobian(2 * observation_.image_points.size(), 6);
    for (int k = 0; k < 6; ++k) {
      const double h = k < 3 ? 1e-6 : 1e-6 * scale;
      Eigen::Matrix<double, 6, 1> step = Eigen::Matrix<double, 6, 1>::Zero();
      step[k] = h;
      jacobian.col(k) = (Residuals(Perturbed(pose, step)) - Residuals(Perturbed(pose, -step))) / (2 * h);
    }
    return jacobian;
  }

  // Gauss–Newton to the minimum, from a start already close to it.
  Pose Polish(Pose pose) const {
    double cost = Residuals(pose).squaredNorm();
    for (int iteration = 0; iteration < 10; ++iteration) {
      const Eigen::MatrixXd j = Jacobian(pose);
      const Eigen::Matrix<double, 6, 1> step = -(j.transpose() * j).ldlt().solve(j.transpose() * Residuals(pose));
      const Pose next = Perturbed(pose, step);
      const double next_cost = Residuals(next).squaredNorm();
      if (!(next_cost < cost)) break;
      pose = next;
      const bool converged = cost - next_cost < 1e-12 * cost;
      cost = next_cost;
      if (converged) break;
    }
    return pose;
  }

 private:
  const Camera& camera_;
  const BoardObservation& observation_;
  std::vector<Eigen::Matrix<double, 8, 8>> whiten_;
};

// d [x y z q1 q2 q3] / d (δ, ε): the position is ε itself; the angles by
// central differences, wrapped to (-180°, 180°].
Eigen::Matrix<double, 6, 6> VectorJacobian(const Pose& pose) {
  Eigen::Matrix<double, 6, 6> g = Eigen::Matrix<double, 6, 6>::Zero();
  g.topRightCorner<3, 3>().setIdentity();
  constexpr double kStep = 1e-7;
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix<double, 6, 1> step = Eigen::Matrix<double, 6, 1>::Zero();
    step[k] = kStep;
    Vector6d difference = VectorFromPose(Perturbed(pose, step), EulerConvention::kXYZ) -
                          VectorFromPose(Perturbed(pose, -step), EulerConvention::kXYZ);
    for (int a = 3; a < 6; ++a) g(a, k) = std::remainder(difference[a], 360.0) / (2 * kStep);
  }
  return g;
}

Pose PoseFromOpenCv(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat rotation;
  cv::Rodrigues(rvec, rotation);
  Pose pose;
  for (int r = 0; r < 3; ++r) {
    pose.position[r] = tvec.at<double>(r);
    for (int c = 0; c < 3; ++c) pose.rotation(r, c) = rotation.at<double>(r, c);
  }
  return pose;
}

double Rms(const Eigen::VectorXd& residuals) { return std::sqrt(residuals.squaredNorm() / (residuals.size() / 2)); }

}  // namespace

const char* PoseStatusName(PoseStatus status) {
  switch (status) {
    case PoseStatus::kOk:
      return "ok";
    case PoseStatus::kNoTarget:
      return "no_target";
    case PoseStatus::kTooFewTags:
      return "too_few_tags";
    case PoseStatus::kHighRms:
      return "high_rms";
    case PoseStatus::kAmbiguous:
      return "ambiguous";
    case PoseStatus::kFailed:
      return "failed";
    case PoseStatus::kUnreadable:
      return "unreadable";
    case PoseStatus::kWrongSize:
      return "wrong_size";
  }
  return "unknown";
}

bool BoardPoseOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (min_tags < 1) return fail("min_tags: must be at least 1");
  if (!(max_rms_px > 0)) return fail("max_rms_px: must be positive");
  if (!(ambiguity_ratio >= 1)) return fail("ambiguity_ratio: must be at least 1");
  return true;
}

Eigen::Matrix3d RotationExp(const Eigen::Vector3d& delta) {
  const double angle = delta.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, delta / angle).toRotationMatrix();
}

Eigen::Vector3d RotationLog(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd angle_axis(rotation);
  return angle_axis.angle() * angle_axis.axis();
}

Eigen::VectorXd ReprojectionResiduals(const Camera& camera, const BoardObservation& observation,
                                      const Pose& camera_from_target) {
  Eigen::VectorXd residuals(2 * observation.image_points.size());
  for (size_t i = 0; i < observation.image_points.size(); ++i) {
    const Eigen::Vector2d projected = camera.Project(camera_from_target * observation.target_points[i]);
    residuals.segment<2>(static_cast<Eigen::Index>(2 * i)) = projected - observation.image_points[i];
  }
  return residuals;
}

BoardPose EstimateBoardPose(const Camera& camera, const BoardObservation& observation,
                            const BoardPoseOptions& options) {
  BoardPose result;
  result.num_tags = observation.NumTags();
  result.num_corners = static_cast<int>(observation.image_points.size());
  if (result.num_tags == 0) {
    result.status = PoseStatus::kNoTarget;
    result.message = "no tag of the target found";
    return result;
  }
  if (result.num_tags < options.min_tags) {
    result.status = PoseStatus::kTooFewTags;
    result.message =
        std::to_string(result.num_tags) + " tags of the target found, " + std::to_string(options.min_tags) + " needed";
    return result;
  }
  // OpenCV's PnP takes radial-tangential and rational coefficients, not the
  // fisheye's: for it, the start poses come from the undistorted normalised
  // points and an identity camera; the polish below uses Camera::Project.
  const bool fisheye = camera.model == CameraModel::kPinholeEqui;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (size_t i = 0; i < observation.image_points.size(); ++i) {
    const Eigen::Vector3d& p = observation.target_points[i];
    std::optional<Eigen::Vector2d> point = observation.image_points[i];
    if (fisheye) point = camera.Undistort(*point);
    if (!point) continue;
    object.emplace_back(p.x(), p.y(), p.z());
    image.emplace_back(point->x(), point->y());
  }
  const cv::Mat k(fisheye ? cv::Matx33d::eye() : camera.CameraMatrix());
  const cv::Mat d = fisheye ? cv::Mat() : camera.DistortionCoefficients();
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    cv::solvePnPGeneric(object, image, k, d, rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
    for (size_t i = 0; i < rvecs.size(); ++i) {
      cv::solvePnPRefineLM(object, image, k, d, rvecs[i], tvecs[i],
                           cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-12));
    }
  } catch (const cv::Exception& e) {  // degenerate input (e.g. every corner on one line)
    result.message = std::string("PnP failed: ") + e.msg;
    return result;
  }
  const PoseProblem problem(camera, observation);
  std::vector<std::pair<double, Pose>> candidates;
  for (size_t i = 0; i < rvecs.size(); ++i) {
    const Pose pose = problem.Polish(PoseFromOpenCv(rvecs[i], tvecs[i]));
    const Eigen::VectorXd residuals = ReprojectionResiduals(camera, observation, pose);
    if (residuals.allFinite()) candidates.emplace_back(Rms(residuals), pose);
  }
  if (candidates.empty()) {
    result.message = "PnP found no pose";
    return result;
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  result.has_pose = true;
  result.camera_from_target = candidates[0].second;
  result.rms_px = candidates[0].first;
  result.alternative_rms_px = candidates.size() > 1 ? candidates[1].first : 0;

  const Eigen::MatrixXd j = problem.Jacobian(result.camera_from_target);
  const Eigen::VectorXd r = problem.Residuals(result.camera_from_target);
  result.variance_factor = r.squaredNorm() / std::max<Eigen::Index>(1, r.size() - 6);
  result.covariance_local = result.variance_factor * (j.transpose() * j).inverse();
  const Eigen::Matrix<double, 6, 6> g = VectorJacobian(result.camera_from_target);
  result.covariance_vector = g * result.covariance_local * g.transpose();

  const double rotation_gap =
      candidates.size() > 1 ? RadToDeg(RotationDistance(candidates[0].second.rotation, candidates[1].second.rotation))
                            : 0;
  if (result.rms_px > options.max_rms_px) {
    result.status = PoseStatus::kHighRms;
    result.message = "reprojection RMS " + FormatSignificant(result.rms_px) + " px > " + FormatSignificant(options.max_rms_px) + " px";
  } else if (candidates.size() > 1 && rotation_gap > 1 &&
             result.alternative_rms_px < options.ambiguity_ratio * result.rms_px) {
    result.status = PoseStatus::kAmbiguous;
    result.message = "two poses " + FormatSignificant(rotation_gap) + " deg apart fit almost equally well (RMS " +
                     FormatSignificant(result.rms_px) + " and " + FormatSignificant(result.alternative_rms_px) + " px)";
  } else {
    result.status = PoseStatus::kOk;
  }
  return result;
}

}  // namespace hexcal

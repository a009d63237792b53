#include "core/point_fit.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <set>

#include <Eigen/SVD>

#include "core/csv.h"
#include "core/forward_kinematics.h"

namespace hexcal {
namespace {

struct PointPair {
  Eigen::Vector3d known, seen;
  double weight = 1;  // 1/σ²
  std::string name;
};

// The measured points paired with the reflectors of their names.
StatusOr<std::vector<PointPair>> PairPoints(const std::vector<NamedPoint>& reflectors,
                                            const std::vector<NamedPoint>& measured) {
  std::vector<PointPair> pairs;
  std::set<std::string> names;
  for (const NamedPoint& m : measured) {
    if (!names.insert(m.name).second) return Status::BadInput("point '" + m.name + "' is measured twice");
    // 1/σ² must be a finite, non-zero weight.
    if (!(m.sigma > 1e-100 && m.sigma < 1e100))
      return Status::BadInput("point '" + m.name + "': its sigma must be a positive number between 1e-100 and 1e100");
    if (!m.position.allFinite()) return Status::BadInput("point '" + m.name + "': a coordinate is not finite");
    auto known = std::find_if(reflectors.begin(), reflectors.end(), [&](const NamedPoint& r) { return r.name == m.name; });
    if (known == reflectors.end()) return Status::BadInput("point '" + m.name + "' is not one of the reflectors");
    pairs.push_back({known->position, m.position, 1 / (m.sigma * m.sigma), m.name});
  }
  if (pairs.size() < 3)
    return Status::BadInput(std::to_string(pairs.size()) + " points measured: a pose needs 3 or more reflectors");
  return pairs;
}

// Weighted Kabsch: the rotation and translation minimising Σ w |R p + t − m|².
Pose WeightedKabsch(const std::vector<PointPair>& pairs) {
  double total = 0;
  Eigen::Vector3d known_centre = Eigen::Vector3d::Zero(), seen_centre = Eigen::Vector3d::Zero();
  for (const PointPair& p : pairs) {
    total += p.weight;
    known_centre += p.weight * p.known;
    seen_centre += p.weight * p.seen;
  }
  known_centre /= total;
  seen_centre /= total;
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (const PointPair& p : pairs) cross += p.weight * (p.known - known_centre) * (p.seen - seen_centre).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
  fix(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  Pose pose;
  pose.rotation = svd.matrixV() * fix * svd.matrixU().transpose();
  pose.position = seen_centre - pose.rotation * known_centre;
  return pose;
}

// The reflectors' spread: its smallest over its largest principal axis.
double Flatness(const std::vector<PointPair>& pairs) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const PointPair& p : pairs) centre += p.known;
  centre /= static_cast<double>(pairs.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const PointPair& p : pairs) scatter += (p.known - centre) * (p.known - centre).transpose();
  const Eigen::Vector3d values = Eigen::JacobiSVD<Eigen::Matrix3d>(scatter).singularValues();
  return values[0] > 0 ? std::sqrt(values[1] / values[0]) : 0;
}

// ∂(R p + t)/∂[δt, θ] for the increment R ← exp([θ]×) R, t ← t + δt.
Eigen::Matrix<double, 3, 6> PointJacobian(const Pose& pose, const Eigen::Vector3d& known) {
  const Eigen::Vector3d q = pose.rotation * known;
  Eigen::Matrix3d skew;
  skew << 0, -q.z(), q.y(), q.z(), 0, -q.x(), -q.y(), q.x(), 0;
  Eigen::Matrix<double, 3, 6> jacobian;
  jacobian << Eigen::Matrix3d::Identity(), -skew;
  return jacobian;
}

// (JᵀWJ)⁻¹: the covariance of the increment [δt, θ].
Matrix6d IncrementCovariance(const Pose& pose, const std::vector<PointPair>& pairs) {
  Matrix6d normal = Matrix6d::Zero();
  for (const PointPair& p : pairs) {
    const Eigen::Matrix<double, 3, 6> jacobian = PointJacobian(pose, p.known);
    normal += p.weight * jacobian.transpose() * jacobian;
  }
  return normal.inverse();
}

// The covariance of VectorFromPose(pose, convention), the increment's mapped by central differences.
Matrix6d PoseCovariance(const Pose& pose, const std::vector<PointPair>& pairs, EulerConvention convention) {
  Matrix6d map;
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vector6d step = Vector6d::Zero();
    step[k] = kStep;
    map.col(k) = (VectorFromPose(ApplyIncrement(pose, step), convention) -
                  VectorFromPose(ApplyIncrement(pose, -step), convention)) /
                 (2 * kStep);
  }
  return map * IncrementCovariance(pose, pairs) * map.transpose();
}

double Residual(const Pose& pose, const PointPair& p) { return (pose.rotation * p.known + pose.position - p.seen).norm(); }

}  // namespace

namespace {

// Bad input when no distance between two measured points is within a
// factor 2 of their reflectors' (one wrong point leaves the others' right):
// another length unit, or other reflectors.
Status CheckScale(const std::vector<PointPair>& pairs) {
  double closest = 0;  // the ratio nearest 1, on a log scale
  for (size_t i = 0; i < pairs.size(); ++i)
    for (size_t j = i + 1; j < pairs.size(); ++j) {
      const double ratio = (pairs[i].seen - pairs[j].seen).norm() / (pairs[i].known - pairs[j].known).norm();
      if (closest == 0 || std::abs(std::log(ratio)) < std::abs(std::log(closest))) closest = ratio;
    }
  if (closest > 0.5 && closest < 2) return Status::Ok();
  // Distances that overflow (coordinates near 1e300) give no ratio.
  if (!std::isfinite(closest)) return Status::BadInput("the points' coordinates are too large to fit");
  return Status::BadInput("the measured points are " + FormatSignificant(closest) +
                          " times as far apart as their reflectors: are they in another length unit?");
}

// With 4 or more points: the point farthest from where the others put it,
// in σ of that difference (its own noise and the others' fit's, Mahalanobis),
// when that is beyond kPointOutlierSigmas.
Status CheckOutlier(const std::vector<PointPair>& pairs) {
  if (pairs.size() < 4) return Status::Ok();
  double worst_sigmas = 0, worst_distance = 0;
  const PointPair* worst = nullptr;
  for (size_t k = 0; k < pairs.size(); ++k) {
    std::vector<PointPair> others = pairs;
    others.erase(others.begin() + static_cast<long>(k));
    const Pose pose = WeightedKabsch(others);
    const Eigen::Vector3d difference = pose.rotation * pairs[k].known + pose.position - pairs[k].seen;
    const Eigen::Matrix<double, 3, 6> jacobian = PointJacobian(pose, pairs[k].known);
    const Eigen::Matrix3d covariance = jacobian * IncrementCovariance(pose, others) * jacobian.transpose() +
                                       Eigen::Matrix3d::Identity() / pairs[k].weight;
    const double sigmas = std::sqrt(difference.dot(covariance.ldlt().solve(difference)));
    if (sigmas > worst_sigmas) worst_sigmas = sigmas, worst_distance = difference.norm(), worst = &pairs[k];
  }
  if (worst_sigmas <= kPointOutlierSigmas) return Status::Ok();
  return Status::BadInput("point '" + worst->name + "' lies " + FormatSignificant(worst_distance) + " (" +
                          FormatSignificant(worst_sigmas) + " sigma) from where the other " +
                          std::to_string(pairs.size() - 1) + " points put it: a wrong reflector or reading");
}

}  // namespace

StatusOr<PointFit> FitPointPose(const std::vector<NamedPoint>& reflectors, const std::vector<NamedPoint>& measured) {
  StatusOr<std::vector<PointPair>> pairs = PairPoints(reflectors, measured);
  if (!pairs.ok()) return pairs.status();
  // Beyond 1e100 the squares in the scatter and cross-covariance overflow, and
  // NaN makes every later test (flatness, scale) answer at random.
  constexpr double kMaxCoordinate = 1e100;
  for (const PointPair& p : *pairs)
    if (p.known.cwiseAbs().maxCoeff() > kMaxCoordinate || p.seen.cwiseAbs().maxCoeff() > kMaxCoordinate)
      return Status::BadInput("the points' coordinates are too large to fit");
  constexpr double kMinFlatness = 1e-6;  // collinear: the rotation about the line is free
  if (Flatness(*pairs) < kMinFlatness) return Status::BadInput("the measured reflectors lie on one line");
  if (Status s = CheckScale(*pairs); !s.ok()) return s;
  if (Status s = CheckOutlier(*pairs); !s.ok()) return s;
  PointFit fit;
  fit.pose = WeightedKabsch(*pairs);
  // Coordinates near the double range (1e300) overflow the cross-covariance.
  if (!fit.pose.position.allFinite() || !fit.pose.rotation.allFinite())
    return Status::BadInput("the points' coordinates are too large to fit");
  fit.covariance = PoseCovariance(fit.pose, *pairs, EulerConvention::kXYZ);
  double sum = 0;
  for (const PointPair& p : *pairs) {
    fit.residuals.push_back(Residual(fit.pose, p));
    sum += fit.residuals.back() * fit.residuals.back();
  }
  fit.rms = std::sqrt(sum / static_cast<double>(pairs->size()));
  return fit;
}

Matrix6d PointPoseCovariance(const Pose& pose, const std::vector<Eigen::Vector3d>& known,
                             const std::vector<double>& sigmas, EulerConvention convention) {
  assert(known.size() == sigmas.size() && known.size() >= 3);
  std::vector<PointPair> pairs;
  for (size_t k = 0; k < known.size(); ++k)
    pairs.push_back({known[k], pose * known[k], 1 / (sigmas[k] * sigmas[k]), ""});
  return PoseCovariance(pose, pairs, convention);
}

StatusOr<std::pair<double, double>> PoseSigmaOfReflectors(const std::vector<NamedPoint>& reflectors, double sigma) {
  std::vector<NamedPoint> seen = reflectors;
  for (NamedPoint& point : seen) point.sigma = sigma;
  StatusOr<PointFit> fit = FitPointPose(reflectors, seen);
  if (!fit.ok()) return fit.status();
  return std::pair<double, double>(std::sqrt(fit->covariance.topLeftCorner<3, 3>().trace() / 3),
                                   std::sqrt(fit->covariance.bottomRightCorner<3, 3>().trace() / 3));
}

}  // namespace hexcal

#include "core/point_fit.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

namespace hexcal {
namespace {

using ::testing::HasSubstr;

// Four reflectors on a 30 cm platform, not coplanar (units: mm).
std::vector<NamedPoint> Reflectors() {
  return {{"R1", {150, 0, 10}}, {"R2", {-75, 130, 0}}, {"R3", {-75, -130, 25}}, {"R4", {0, 0, 60}}};
}

Pose TruePose() {
  return PoseFromVector((Vector6d() << 120, -340, 2150, 12, -7, 33).finished(), EulerConvention::kXYZ);
}

// The reflectors as the tracker sees them at `pose`, with N(0, σ²) noise per coordinate.
std::vector<NamedPoint> Seen(const Pose& pose, double sigma, std::mt19937& random) {
  std::normal_distribution<double> noise(0, sigma);
  std::vector<NamedPoint> seen;
  for (const NamedPoint& r : Reflectors()) {
    const Eigen::Vector3d at = pose.rotation * r.position + pose.position;
    seen.push_back({r.name, at + Eigen::Vector3d(noise(random), noise(random), noise(random)), sigma});
  }
  return seen;
}

TEST(PointFit, NoiselessPointsGiveThePoseExactly) {
  std::mt19937 random(1);
  std::vector<NamedPoint> seen = Seen(TruePose(), 0, random);
  for (NamedPoint& p : seen) p.sigma = 0.02;
  StatusOr<PointFit> fit = FitPointPose(Reflectors(), seen);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_LT((fit->pose.position - TruePose().position).norm(), 1e-9);
  EXPECT_LT(RotationDistance(fit->pose.rotation, TruePose().rotation), 1e-12);
  EXPECT_LT(fit->rms, 1e-9);
}

// The stated covariance against the scatter of 3000 noisy fits.
TEST(PointFit, CovarianceMatchesMonteCarlo) {
  std::mt19937 random(7);
  const double sigma = 0.03;
  StatusOr<PointFit> first = FitPointPose(Reflectors(), Seen(TruePose(), sigma, random));
  ASSERT_TRUE(first.ok());
  const Vector6d truth = VectorFromPose(TruePose(), EulerConvention::kXYZ);
  Matrix6d scatter = Matrix6d::Zero();
  constexpr int kTrials = 3000;
  for (int k = 0; k < kTrials; ++k) {
    StatusOr<PointFit> fit = FitPointPose(Reflectors(), Seen(TruePose(), sigma, random));
    ASSERT_TRUE(fit.ok());
    const Vector6d error = VectorFromPose(fit->pose, EulerConvention::kXYZ) - truth;
    scatter += error * error.transpose() / kTrials;
  }
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(std::sqrt(scatter(i, i)), std::sqrt(first->covariance(i, i)), 0.05 * std::sqrt(first->covariance(i, i)))
        << "coordinate " << i;
}

std::string ErrorOf(const std::vector<NamedPoint>& seen) {
  StatusOr<PointFit> fit = FitPointPose(Reflectors(), seen);
  return fit.ok() ? "" : fit.status().message();
}

TEST(PointFit, BadPointsAreNamed) {
  std::mt19937 random(3);
  const std::vector<NamedPoint> good = Seen(TruePose(), 0.02, random);
  EXPECT_THAT(ErrorOf({good[0], good[1]}), HasSubstr("2 points measured: a pose needs 3 or more reflectors"));
  EXPECT_THAT(ErrorOf({good[0], good[1], good[1]}), HasSubstr("point 'R2' is measured twice"));
  std::vector<NamedPoint> unknown = good;
  unknown[2].name = "R9";
  EXPECT_THAT(ErrorOf(unknown), HasSubstr("point 'R9' is not one of the reflectors"));
  std::vector<NamedPoint> no_sigma = good;
  no_sigma[1].sigma = 0;
  EXPECT_THAT(ErrorOf(no_sigma), HasSubstr("point 'R2': its sigma must be a positive number"));
  std::vector<NamedPoint> nan = good;
  nan[3].position.y() = std::nan("");
  EXPECT_THAT(ErrorOf(nan), HasSubstr("point 'R4': a coordinate is not finite"));
  std::vector<NamedPoint> metres = good;  // the tracker's file in m, the reflectors in mm
  for (NamedPoint& p : metres) p.position /= 1000, p.sigma /= 1000;
  EXPECT_THAT(ErrorOf(metres), HasSubstr("0.001 times as far apart as their reflectors: are they in another length unit?"));
  std::vector<NamedPoint> off = good;
  off[2].position.x() += 1000;  // 1 m off
  EXPECT_THAT(ErrorOf(off), HasSubstr("point 'R3' lies 1e+03 ("));
}

TEST(PointFit, CollinearReflectorsAreRefused) {
  const std::vector<NamedPoint> line = {{"A", {0, 0, 0}}, {"B", {100, 0, 0}}, {"C", {250, 0, 0}}};
  std::vector<NamedPoint> seen = line;
  for (NamedPoint& p : seen) p.sigma = 0.02;
  StatusOr<PointFit> fit = FitPointPose(line, seen);
  ASSERT_FALSE(fit.ok());
  EXPECT_THAT(fit.status().message(), HasSubstr("lie on one line"));
}

}  // namespace
}  // namespace hexcal

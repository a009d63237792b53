#include "core/point_fit.h"
#include "core/point_repeatability.h"
#include "core/reflector_estimate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
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

// `count` sets named prefix0, prefix1, ...: the reflectors seen with noise σ
// at pose_of(k) (x, y, z in mm, XYZ Euler angles in degrees).
PointSets SetsAt(int count, const std::string& prefix, double sigma, std::mt19937& random,
                 const std::function<Vector6d(int)>& pose_of) {
  PointSets sets;
  for (int k = 0; k < count; ++k) {
    const Pose pose = PoseFromVector(pose_of(k), EulerConvention::kXYZ);
    sets.push_back({prefix + std::to_string(k), Seen(pose, sigma, random)});
  }
  return sets;
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

// The noise a tracker implies for the pose, before measuring: the σ the Monte
// Carlo test above checks, at the reflectors' frame.
TEST(PointFit, PoseSigmaOfReflectorsMatchesTheFitsCovariance) {
  std::mt19937 random(2);
  std::vector<NamedPoint> seen = Seen(Pose{}, 0, random);
  for (NamedPoint& p : seen) p.sigma = 0.02;
  StatusOr<PointFit> fit = FitPointPose(Reflectors(), seen);
  StatusOr<std::pair<double, double>> sigma = PoseSigmaOfReflectors(Reflectors(), 0.02);
  ASSERT_TRUE(fit.ok() && sigma.ok());
  EXPECT_NEAR(sigma->first, std::sqrt(fit->covariance.topLeftCorner<3, 3>().trace() / 3), 1e-12);
  EXPECT_NEAR(sigma->second, std::sqrt(fit->covariance.bottomRightCorner<3, 3>().trace() / 3), 1e-12);
  EXPECT_LT(sigma->first, 0.02);  // 4 points average their noise
}

TEST(PointFit, HugeCoordinatesAreAnErrorNotNaN) {
  std::vector<NamedPoint> reflectors = Reflectors(), seen = Reflectors();
  for (NamedPoint& p : reflectors) p.position *= 1e305;
  for (NamedPoint& p : seen) {
    p.position *= 1e305;
    p.sigma = 1e50;
  }
  StatusOr<PointFit> fit = FitPointPose(reflectors, seen);
  ASSERT_FALSE(fit.ok());
  EXPECT_THAT(fit.status().message(), HasSubstr("too large"));
  seen = Reflectors();
  for (NamedPoint& p : seen) p.sigma = 1e300;  // its weight 1/σ² underflows to 0
  fit = FitPointPose(Reflectors(), seen);
  ASSERT_FALSE(fit.ok());
  EXPECT_THAT(fit.status().message(), HasSubstr("sigma"));
}

TEST(PointFit, CollinearReflectorsAreRefused) {
  const std::vector<NamedPoint> line = {{"A", {0, 0, 0}}, {"B", {100, 0, 0}}, {"C", {250, 0, 0}}};
  std::vector<NamedPoint> seen = line;
  for (NamedPoint& p : seen) p.sigma = 0.02;
  StatusOr<PointFit> fit = FitPointPose(line, seen);
  ASSERT_FALSE(fit.ok());
  EXPECT_THAT(fit.status().message(), HasSubstr("lie on one line"));
}

// Without a reflector file, the shape is recovered from the poses: every
// pairwise distance within a few σ/√poses, a reflector one set lacks included.
TEST(ReflectorEstimate, RecoversTheShapeFromNoisyPoses) {
  std::mt19937 random(3);
  const double sigma = 0.02;
  PointSets sets = SetsAt(20, "pose", sigma, random,
                          [](int k) { return (Vector6d() << 10 * k, -5 * k, 2000, 2 * k, -k, 3 * k).finished(); });
  sets[0].points.pop_back();  // R4 not seen at the first pose
  StatusOr<std::vector<NamedPoint>> estimate = EstimateReflectors(sets);
  ASSERT_TRUE(estimate.ok()) << estimate.status().message();
  ASSERT_EQ(estimate->size(), 4u);
  const std::vector<NamedPoint> truth = Reflectors();
  const auto find = [&](const std::string& name) {
    for (const NamedPoint& p : *estimate)
      if (p.name == name) return p.position;
    ADD_FAILURE() << name << " not estimated";
    return Eigen::Vector3d(Eigen::Vector3d::Zero());
  };
  for (size_t a = 0; a < truth.size(); ++a)
    for (size_t b = a + 1; b < truth.size(); ++b)
      EXPECT_NEAR((find(truth[a].name) - find(truth[b].name)).norm(), (truth[a].position - truth[b].position).norm(),
                  4 * sigma * std::sqrt(2.0 / 19))
          << truth[a].name << "-" << truth[b].name;
}

TEST(ReflectorEstimate, NeedsAPoseWithThreePoints) {
  PointSets sets = {{"p1", {{"R1", {0, 0, 0}, 0.01}, {"R2", {1, 0, 0}, 0.01}}}};
  StatusOr<std::vector<NamedPoint>> estimate = EstimateReflectors(sets);
  ASSERT_FALSE(estimate.ok());
  EXPECT_THAT(estimate.status().message(), HasSubstr("3 or more points"));
}

// 50 repeats of one pose (the tracker bumped a little between sets): the
// measured σ is the simulated one within 15 % (its standard error is 4 %), and
// with the declared σ half the truth the ratio says 2.
TEST(PointRepeatability, MeasuresTheSimulatedNoise) {
  std::mt19937 random(11);
  const double sigma = 0.03;
  PointSets sets = SetsAt(50, "rep", sigma, random,
                          [](int k) { return (Vector6d() << 120 + 0.01 * k, -340, 2150, 12, -7, 33).finished(); });
  StatusOr<Repeatability> r = MeasurePointRepeatability(sets);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->degrees_of_freedom, 3 * 200 - 300 - 12 + 6);
  EXPECT_NEAR(r->measured_sigma, sigma, 0.15 * sigma);
  EXPECT_NEAR(r->ratio, 1, 0.15);
  for (PointSet& set : sets)
    for (NamedPoint& point : set.points) point.sigma = sigma / 2;
  StatusOr<Repeatability> understated = MeasurePointRepeatability(sets);
  ASSERT_TRUE(understated.ok());
  EXPECT_NEAR(understated->ratio, 2, 0.3);
}

TEST(PointRepeatability, NeedsThreeSets) {
  std::mt19937 random(1);
  PointSets sets = {{"a", Seen(TruePose(), 0.02, random)}, {"b", Seen(TruePose(), 0.02, random)}};
  StatusOr<Repeatability> r = MeasurePointRepeatability(sets);
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), HasSubstr("3 or more"));
}

}  // namespace
}  // namespace hexcal

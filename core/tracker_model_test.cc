#include "core/tracker_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/planning_model.h"
#include "core/point_fit.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

Robot Inria() {
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");  // cm, Euler xyz
  EXPECT_TRUE(robot.ok());
  return *robot;
}

// Four reflectors on top of inria-left-hand's platform (radius about 7.9 cm), not coplanar, cm.
std::vector<Eigen::Vector3d> TopReflectors() { return {{7, 0, 1}, {-3.5, 6, 0.5}, {-3.5, -6, 1.5}, {0, 0.5, 3}}; }

TrackerSettings LinearTracker(const Eigen::Vector3d& position, double sigma0, double per_distance) {
  TrackerSettings settings;
  settings.position = position;
  settings.sigma_law = PointSigmaLaw::kLinear;
  settings.sigma0 = sigma0;
  settings.sigma_per_distance = per_distance;
  return settings;
}

// Four reflectors (±a, 0, 0), (0, ±a, 0) at equal distance from a tracker on
// their axis, so every σ is σ0 + k √(D² + a²). By hand, with w = 1/σ²:
// JᵀWJ = w Σ [I, −[p]×; [p]×, −[p]×²] is block-diagonal (Σ p = 0), the
// position block 4w I, the rotation block w Σ(|p|² I − p pᵀ) = w diag(2a², 2a², 4a²);
// at zero angles the Euler rates are the rotation vector's.
TEST(TrackerModel, PoseCovarianceMatchesTheHandComputedSquare) {
  const Robot robot = Inria();
  const double a = 5, height = 50, distance = 200, sigma0 = 0.0015, k = 6e-6;
  const std::vector<Eigen::Vector3d> square = {{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}};
  StatusOr<TrackerModel> tracker =
      MakeTrackerModel(robot, square, 0.002, LinearTracker({0, 0, height + distance}, sigma0, k));
  ASSERT_TRUE(tracker.ok()) << tracker.status().message();
  const Pose pose = PoseFromVector((Vector6d() << 0, 0, height, 0, 0, 0).finished(), EulerConvention::kXYZ);
  const double sigma = sigma0 + k * std::sqrt(distance * distance + a * a);
  for (double s : ReflectorSigmas(*tracker, pose)) EXPECT_NEAR(s, sigma, 1e-15);
  const double deg2 = RadToDeg(1) * RadToDeg(1);
  Vector6d expected;
  expected << sigma * sigma / 4, sigma * sigma / 4, sigma * sigma / 4, deg2 * sigma * sigma / (2 * a * a),
      deg2 * sigma * sigma / (2 * a * a), deg2 * sigma * sigma / (4 * a * a);
  const Matrix6d covariance = TrackerPoseCovariance(*tracker, robot, pose);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(covariance(i, j), i == j ? expected[i] : 0.0, 1e-6 * expected[i]) << i << "," << j;
}

TEST(TrackerModel, ConstantLawIsPointSigmaAtAnyDistance) {
  TrackerSettings settings;
  settings.position = Eigen::Vector3d(0, 0, 500);
  StatusOr<TrackerModel> tracker = MakeTrackerModel(Inria(), TopReflectors(), 0.002, settings);
  ASSERT_TRUE(tracker.ok());
  EXPECT_EQ(PointSigmaAt(*tracker, 0), 0.002);
  EXPECT_EQ(PointSigmaAt(*tracker, 1e4), 0.002);
}

// Empirical covariance of robot.VectorFromPose over simulated fits (FitPointPose)
// of points with the law's σ at `pose`.
Matrix6d SimulatedCovariance(const TrackerModel& tracker, const Robot& robot, const Pose& pose, int trials) {
  std::mt19937_64& random = hexcal::testing::TestRng();
  std::normal_distribution<double> unit(0, 1);
  const std::vector<double> sigmas = ReflectorSigmas(tracker, pose);
  std::vector<NamedPoint> known;
  for (size_t k = 0; k < tracker.reflectors.size(); ++k)
    known.push_back({"R" + std::to_string(k), tracker.reflectors[k], 0});
  const Vector6d truth = robot.VectorFromPose(pose);
  Matrix6d sum = Matrix6d::Zero();
  for (int n = 0; n < trials; ++n) {
    std::vector<NamedPoint> seen;
    for (size_t k = 0; k < known.size(); ++k) {
      const Eigen::Vector3d noise(unit(random), unit(random), unit(random));
      seen.push_back({known[k].name, pose * known[k].position + sigmas[k] * noise, sigmas[k]});
    }
    StatusOr<PointFit> fit = FitPointPose(known, seen);
    EXPECT_TRUE(fit.ok());
    const Vector6d error = robot.VectorFromPose(fit->pose) - truth;
    sum += error * error.transpose();
  }
  return sum / trials;
}

// The predicted σ of each pose coordinate against 4000 simulated fits, at a
// pose 50 cm from the tracker and one 450 cm away (σ 7 times as large with a
// steep law, 15 µm + 100 µm/m): each within 5 % (the σ of an estimated σ is 1/√8000, 1.1 %).
TEST(TrackerModel, PredictedPoseSigmaMatchesSimulatedFitsNearAndFar) {
  const Robot robot = Inria();
  StatusOr<TrackerModel> tracker =
      MakeTrackerModel(robot, TopReflectors(), 0.002, LinearTracker({0, 0, 100}, 0.0015, 1e-4));
  ASSERT_TRUE(tracker.ok());
  const Pose near = PoseFromVector((Vector6d() << 2, -3, 50, 10, -5, 20).finished(), EulerConvention::kXYZ);
  const Pose far = PoseFromVector((Vector6d() << 30, 440, 10, -15, 8, 60).finished(), EulerConvention::kXYZ);
  Vector6d near_sigma, far_sigma;
  for (const Pose* pose : {&near, &far}) {
    const Matrix6d predicted = TrackerPoseCovariance(*tracker, robot, *pose);
    const Matrix6d simulated = SimulatedCovariance(*tracker, robot, *pose, 4000);
    for (int i = 0; i < 6; ++i) {
      const double p = std::sqrt(predicted(i, i)), s = std::sqrt(simulated(i, i));
      EXPECT_NEAR(s / p, 1.0, 0.05) << (pose == &near ? "near" : "far") << " coordinate " << i;
      (pose == &near ? near_sigma : far_sigma)[i] = p;
    }
  }
  // The position σ scales with the points' σ (near 50 cm: 0.0065; far about 450 cm: 0.047).
  EXPECT_GT(far_sigma.head<3>().mean() / near_sigma.head<3>().mean(), 5);
}

SightScene UnitDiscScene(const Eigen::Vector3d& tracker) {
  SightScene scene;
  scene.tracker = tracker;
  scene.acceptance_deg = 90;
  scene.disc_centre = Eigen::Vector3d::Zero();
  scene.disc_normal = Eigen::Vector3d::UnitZ();
  scene.disc_radius = 1;
  return scene;
}

// A reflector at the origin facing +z, the tracker at 29° and 31° from the
// normal: margins +1° and −1° of a 30° cone.
TEST(TrackerModel, AcceptanceConeMarginIsTheAngleToSpare) {
  for (double angle : {29.0, 31.0}) {
    SightScene scene = UnitDiscScene({10 * std::tan(DegToRad(angle)), 0, 10});
    scene.acceptance_deg = 30;
    const std::array<double, 3> m = ReflectorSightMargins(scene, {0, 0, 0}, Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(m[0], 30 - angle, 1e-9);
  }
  SightScene scene = UnitDiscScene({0, 0, 10});
  scene.acceptance_deg = 30;
  EXPECT_NEAR(ReflectorSightMargins(scene, {0, 0, 0.5}, Eigen::Vector3d::UnitZ())[0], 30, 1e-9);
  EXPECT_NEAR(ReflectorSightMargins(scene, {0, 0, 0.5}, -Eigen::Vector3d::UnitZ())[0], 30 - 180, 1e-9);
}

// The disc of radius 1 in z = 0. From (0.5, 0, −0.1) to (2, 0, 3) the line
// crosses z = 0 at t = 0.1/3.1, x = 0.5 + 1.5·0.1/3.1 = 0.5484 < 1: hidden.
TEST(TrackerModel, DiscBlocksASightLineCrossingItInsideItsRadius) {
  const SightScene scene = UnitDiscScene({2, 0, 3});
  EXPECT_NEAR(ReflectorSightMargins(scene, {0.5, 0, -0.1}, Eigen::Vector3d::UnitX())[1], 0.5 + 0.15 / 3.1 - 1, 1e-12);
  // From (1.5, 0, −0.1) it crosses at x = 1.5 + 0.5·0.1/3.1, outside the disc.
  EXPECT_NEAR(ReflectorSightMargins(scene, {1.5, 0, -0.1}, Eigen::Vector3d::UnitX())[1], 0.5 + 0.05 / 3.1, 1e-12);
  // Above the disc, no crossing: the margin is the nearer end's height, 0.2.
  EXPECT_NEAR(ReflectorSightMargins(scene, {0.5, 0, 0.2}, Eigen::Vector3d::UnitZ())[1], 0.2, 1e-12);
}

// A leg along y at x = 1, z = 0, radius 0.3.
TEST(TrackerModel, LegBlocksASightLinePassingWithinItsRadius) {
  SightScene scene = UnitDiscScene({2, 0, 1});
  scene.disc_radius = 0;
  scene.legs = {{{1, -1, 0}, {1, 1, 0}}};
  scene.leg_radius = 0.3;
  EXPECT_NEAR(ReflectorSightMargins(scene, {0, 0, 1}, Eigen::Vector3d::UnitX())[2], 1 - 0.3, 1e-12);
  scene.tracker = {2, 0, 0.2};
  EXPECT_NEAR(ReflectorSightMargins(scene, {0, 0, 0.2}, Eigen::Vector3d::UnitX())[2], 0.2 - 0.3, 1e-12);
  // A sight line ending before the leg: its end (0.5, 0, 0) is 0.5 from it.
  scene.tracker = {-3, 0, 0};
  EXPECT_NEAR(ReflectorSightMargins(scene, {0.5, 0, 0}, -Eigen::Vector3d::UnitX())[2], 0.5 - 0.3, 1e-12);
}

// Reflectors on top of the platform facing up: a tracker above the platform
// sees every one; one below it sees none (each behind the platform: outside
// its cone and behind the disc), and the planner refuses the pose.
TEST(TrackerModel, PlannerRefusesAPoseWithReflectorsBehindThePlatform) {
  const Robot robot = Inria();
  const Vector6d centre = (Vector6d() << 0, 0, 53, 0, 0, 0).finished();
  ASSERT_TRUE(PlanningModel({robot, NoiseModel{}, std::nullopt}).IsFeasible(centre));
  for (double height : {250.0, -150.0}) {
    TrackerSettings settings;
    settings.position = Eigen::Vector3d(20, 10, height);
    StatusOr<TrackerModel> tracker = MakeTrackerModel(robot, TopReflectors(), 0.002, settings);
    ASSERT_TRUE(tracker.ok());
    PlanningModel model{robot, NoiseModel{}, std::nullopt, *tracker};
    const std::vector<double> margins = LineOfSightMargins(*tracker, robot, robot.PoseFromVector(centre));
    ASSERT_EQ(margins.size(), 12u);
    if (height > 0) {
      EXPECT_TRUE(model.IsFeasible(centre));
      continue;
    }
    EXPECT_FALSE(model.IsFeasible(centre));
    for (int k = 0; k < 4; ++k) {
      EXPECT_LT(margins[3 * k], 0) << "reflector " << k << " outside its cone";
      EXPECT_LT(margins[3 * k + 1], 0) << "reflector " << k << " behind the disc";
    }
  }
}

// One reflector hanging under the platform (within the disc) while the
// tracker looks from above within every cone: the disc hides it, the pose is refused.
TEST(TrackerModel, PlannerRefusesAReflectorUnderThePlatform) {
  const Robot robot = Inria();
  std::vector<Eigen::Vector3d> reflectors = TopReflectors();
  reflectors[3] = {0, 0.5, -2};
  TrackerSettings settings;
  settings.position = Eigen::Vector3d(0, 0, 300);
  StatusOr<TrackerModel> tracker = MakeTrackerModel(robot, reflectors, 0.002, settings);
  ASSERT_TRUE(tracker.ok());
  const Vector6d centre = (Vector6d() << 0, 0, 53, 0, 0, 0).finished();
  const std::vector<double> margins = LineOfSightMargins(*tracker, robot, robot.PoseFromVector(centre));
  EXPECT_GT(margins[9], 0);  // within its cone
  EXPECT_LT(margins[10], 0);  // the disc hides it
  EXPECT_FALSE((PlanningModel{robot, NoiseModel{}, std::nullopt, *tracker}.IsFeasible(centre)));
}

TEST(TrackerModel, RefusesCollinearReflectorsAndBadSettings) {
  const Robot robot = Inria();
  StatusOr<TrackerModel> line = MakeTrackerModel(robot, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 0.002, {});
  ASSERT_FALSE(line.ok());
  EXPECT_THAT(line.status().message(), HasSubstr("one line"));
  TrackerSettings no_position;
  no_position.sigma_law = PointSigmaLaw::kLinear;
  no_position.sigma0 = 0.001;
  StatusOr<TrackerModel> bad = MakeTrackerModel(robot, TopReflectors(), 0.002, no_position);
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(), HasSubstr("tracker.sigma_law: linear needs tracker.position"));
}

// The section round-trips through session.yaml, and a value out of range is
// named by its key.
TEST(TrackerModel, SessionTrackerSectionRoundTripsAndNamesBadKeys) {
  hexcal::testing::TempDir dir;
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.instrument = Instrument::kPoints;
  config.points = "points.txt";
  config.point_sigma = 0.002;
  config.tracker = LinearTracker({150, -20.5, 210}, 0.0015, 6e-6);
  config.tracker->acceptance_deg = 35;
  config.tracker->leg_radius = 1.25;
  config.tracker->reflector_normal = {0, 0.1, 1};
  const std::string session = dir.File("s");
  ASSERT_TRUE(InitSession(session, config).ok());
  StatusOr<SessionConfig> loaded = LoadSessionConfig(session);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  ASSERT_TRUE(loaded->tracker && loaded->tracker->position);
  EXPECT_EQ(*loaded->tracker->position, *config.tracker->position);
  EXPECT_EQ(loaded->tracker->sigma_law, PointSigmaLaw::kLinear);
  EXPECT_EQ(loaded->tracker->sigma0, 0.0015);
  EXPECT_EQ(loaded->tracker->sigma_per_distance, 6e-6);
  EXPECT_EQ(loaded->tracker->acceptance_deg, 35);
  EXPECT_EQ(loaded->tracker->leg_radius, 1.25);
  EXPECT_EQ(loaded->tracker->reflector_normal, config.tracker->reflector_normal);

  std::string text = hexcal::testing::ReadTextFile(session + "/session.yaml");
  const size_t key = text.find("sigma_per_distance: ");
  ASSERT_NE(key, std::string::npos);
  text.replace(key, text.find('\n', key) - key, "sigma_per_distance: 0.01");
  hexcal::testing::WriteTextFile(session + "/session.yaml", text);
  StatusOr<SessionConfig> bad = LoadSessionConfig(session);
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(), HasSubstr("tracker.sigma_per_distance: must be at most 0.001"));
}

// docs/session.md carries the table the code generates (keys, flags, ranges, defaults).
TEST(TrackerModel, DocsListEveryTrackerKey) {
  const std::string docs = hexcal::testing::ReadTextFile((hexcal::testing::SourceDir() / "docs" / "session.md").string());
  const std::string table = OptionsMarkdownTable(TrackerSettingsOptions(), "tracker-");
  EXPECT_NE(docs.find(table), std::string::npos) << "docs/session.md needs this table:\n" << table;
}

}  // namespace
}  // namespace hexcal

// The section 7 study: exact data recover the true robot; the numbers depend
// only on the seed (not on the thread count or the other sets listed); noise
// and perturbations stay within their half-widths; a wider pose set beats a
// cramped one; bad requests fail with a reason.
#include "core/simulation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/candidates.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

std::vector<Vector6d> CandidatePoses(const Robot& robot, CandidateKind kind, int count) {
  CandidateOptions options;
  options.kind = kind;
  options.count = count;
  const StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
  EXPECT_TRUE(set.ok()) << set.status().message();
  return set.ok() ? set->poses : std::vector<Vector6d>{};
}

// Poses in a small box around the centre of the workspace: a poorly conditioned set.
std::vector<Vector6d> CrampedPoses(int count) {
  std::vector<Vector6d> poses;
  for (int j = 0; j < count; ++j) {
    Vector6d v;
    v << Uniform(-0.3, 0.3), Uniform(-0.3, 0.3), Uniform(53.4, 53.8), Uniform(-2, 2), Uniform(-2, 2), Uniform(-2, 2);
    poses.push_back(v);
  }
  return poses;
}

SimulationOptions SmallStudy(int runs) {
  SimulationOptions options;
  options.runs = runs;
  options.seed = 7;
  return options;
}

TEST(Simulation, ExactMeasurementsRecoverTheTrueRobot) {
  const Robot nominal = Preset("inria-left-hand");
  SimulationOptions options = SmallStudy(3);
  options.noise = {0, 0, 0};
  const std::vector<SimulationPoseSet> sets = {
      RandomPoseSet(12), FixedPoseSet("uniform", CandidatePoses(nominal, CandidateKind::kUniform, 15))};
  StatusOr<SimulationResult> result = Simulate(nominal, sets, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  ASSERT_EQ(result->sets.size(), 2u);
  for (const SetError& set : result->sets) {
    EXPECT_EQ(set.runs, 3);
    EXPECT_EQ(set.failed_runs, 0);
    EXPECT_LT(set.mean + 3 * set.std, 1e-9) << set.name;
    EXPECT_LT(set.mean_estimate_error, 1e-9);
  }
  EXPECT_EQ(result->sets[0].name, "random");
  EXPECT_EQ(result->sets[0].poses, 12);
  EXPECT_EQ(result->sets[1].poses, 15);
  EXPECT_GT(result->before.mean, 0.1);
}

TEST(Simulation, TheSeedAloneDecidesTheNumbers) {
  const Robot nominal = Preset("inria-left-hand");
  const std::vector<Vector6d> fixed = CandidatePoses(nominal, CandidateKind::kUniform, 12);
  SimulationOptions one_thread = SmallStudy(4), two_threads = SmallStudy(4);
  one_thread.num_threads = 1;
  two_threads.num_threads = 2;
  StatusOr<SimulationResult> a = Simulate(nominal, {RandomPoseSet(10), FixedPoseSet("fixed", fixed)}, one_thread);
  StatusOr<SimulationResult> b = Simulate(nominal, {FixedPoseSet("fixed", fixed), RandomPoseSet(10)}, two_threads);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->true_parameters, b->true_parameters);
  EXPECT_EQ(a->sets[0].mean, b->sets[1].mean);  // random, listed first and second
  EXPECT_EQ(a->sets[0].std, b->sets[1].std);
  EXPECT_EQ(a->sets[1].mean, b->sets[0].mean);
  EXPECT_EQ(*a->sets[1].ratio_to_random, *b->sets[0].ratio_to_random);
  EXPECT_EQ(*a->sets[0].ratio_to_random, 1.0);

  SimulationOptions other_seed = one_thread;
  other_seed.seed = 8;
  StatusOr<SimulationResult> c = Simulate(nominal, {RandomPoseSet(10)}, other_seed);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(c->sets[0].mean, a->sets[0].mean);
}

TEST(Simulation, PerturbationAndNoiseStayWithinTheirHalfWidths) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5, 3);
  const ParameterVector offset = ParametersOf(truth) - ParametersOf(nominal);
  EXPECT_LE(offset.cwiseAbs().maxCoeff(), 0.5);
  EXPECT_GT(offset.cwiseAbs().maxCoeff(), 0.3);  // uniform over 42 draws reaches near the edge
  EXPECT_EQ(ParametersOf(PerturbedRobot(nominal, 0.5, 3)), ParametersOf(truth));

  const std::vector<Vector6d> poses = CandidatePoses(nominal, CandidateKind::kUniform, 20);
  const NoiseModel noise{0.01, 0.1, 0.02};
  std::mt19937_64 rng(5);
  const std::vector<Measurement> measurements = SimulateMeasurements(truth, poses, noise, &rng);
  ASSERT_EQ(measurements.size(), poses.size());
  for (size_t j = 0; j < poses.size(); ++j) {
    const Vector6d d = measurements[j].pose - poses[j];
    EXPECT_LE(d.head<3>().cwiseAbs().maxCoeff(), noise.position);
    EXPECT_LE(d.tail<3>().cwiseAbs().maxCoeff(), noise.angle_deg);
    const LegReadings exact = InverseKinematics(truth, truth.PoseFromVector(poses[j]));
    EXPECT_LE((measurements[j].legs - exact).cwiseAbs().maxCoeff(), noise.leg);
    EXPECT_GT((measurements[j].legs - exact).cwiseAbs().maxCoeff(), 0);
  }
}

TEST(Simulation, AWidePoseSetBeatsACrampedOne) {
  const Robot nominal = Preset("inria-left-hand");
  const std::vector<SimulationPoseSet> sets = {
      FixedPoseSet("cramped", CrampedPoses(18)),
      FixedPoseSet("uniform", CandidatePoses(nominal, CandidateKind::kUniform, 18))};
  StatusOr<SimulationResult> result = Simulate(nominal, sets, SmallStudy(5));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_LT(result->sets[1].mean, 0.5 * result->sets[0].mean);
  EXPECT_LT(result->sets[1].mean, result->before.mean);
  EXPECT_FALSE(result->sets[0].ratio_to_random.has_value());  // no random set listed
}

TEST(Simulation, SweepNestsTheSetsAndSkipsShortOnes) {
  const Robot nominal = Preset("inria-left-hand");
  const std::vector<SimulationPoseSet> sets = {
      RandomPoseSet(18), FixedPoseSet("uniform", CandidatePoses(nominal, CandidateKind::kUniform, 9))};
  StatusOr<SweepResult> sweep = SimulateSweep(nominal, sets, 8, 10, SmallStudy(2));
  ASSERT_TRUE(sweep.ok()) << sweep.status().message();
  ASSERT_EQ(sweep->points.size(), 3u);
  EXPECT_EQ(sweep->points[0].poses, 8);
  EXPECT_EQ(sweep->points[0].sets.size(), 2u);
  EXPECT_EQ(sweep->points[1].sets.size(), 2u);
  ASSERT_EQ(sweep->points[2].sets.size(), 1u);  // the fixed set has only 9 poses
  EXPECT_EQ(sweep->points[2].sets[0].name, "random");
  EXPECT_EQ(sweep->points[2].sets[0].poses, 10);
  EXPECT_TRUE(sweep->points[1].sets[1].ratio_to_random.has_value());

  const Status too_few = SimulateSweep(nominal, sets, 6, 10, SmallStudy(1)).status();
  EXPECT_EQ(too_few.message(), "sweep: 6:10 is not MIN:MAX with 7 <= MIN <= MAX <= 10000");
  EXPECT_EQ(too_few.option(), "sweep");
}

TEST(Simulation, BadRequestsAreErrors) {
  const Robot nominal = Preset("inria-left-hand");
  EXPECT_THAT(Simulate(nominal, {}, SmallStudy(1)).status().message(), HasSubstr("at least one pose set"));
  EXPECT_THAT(Simulate(nominal, {RandomPoseSet(5)}, SmallStudy(1)).status().message(),
              HasSubstr("'random' has 5 poses"));
  EXPECT_THAT(Simulate(nominal, {RandomPoseSet(8), RandomPoseSet(9)}, SmallStudy(1)).status().message(),
              HasSubstr("listed twice"));
  EXPECT_THAT(Simulate(nominal, {RandomPoseSet(8)}, SmallStudy(0)).status().message(),
              HasSubstr("runs: must be at least 1, got 0"));
  // A degenerate fixed set fails in every run: an error with the calibration's reason.
  const std::vector<Vector6d> one_pose(8, CandidatePoses(nominal, CandidateKind::kUniform, 1)[0]);
  EXPECT_THAT(Simulate(nominal, {FixedPoseSet("same", one_pose)}, SmallStudy(2)).status().message(),
              HasSubstr("failed in every run; first: degenerate pose set"));
  Robot no_box = nominal;
  no_box.limits.pose_box.reset();
  no_box.limits.sampling_box.reset();
  EXPECT_THAT(Simulate(no_box, {RandomPoseSet(8)}, SmallStudy(1)).status().message(), HasSubstr("pose_box"));
}

TEST(Simulation, CancelStopsTheStudy) {
  const Robot nominal = Preset("inria-left-hand");
  std::atomic<bool> cancel{false};
  SimulationOptions options = SmallStudy(50);
  options.num_threads = 1;
  StatusOr<SimulationResult> result =
      Simulate(nominal, {FixedPoseSet("uniform", CandidatePoses(nominal, CandidateKind::kUniform, 10))}, options,
               {[&](int done, int) { cancel = done >= 2; }, &cancel});
  ASSERT_FALSE(result.ok());
  EXPECT_TRUE(result.status().cancelled());
}

}  // namespace
}  // namespace hexcal

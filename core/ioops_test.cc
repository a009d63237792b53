// IOOPS on the paper's robot: the done-when targets of the planner (O2 >= 0.0139,
// Table 2), DETMAX monotonicity, Tabu bookkeeping, determinism and errors.
#include "core/ioops.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <random>

#include "core/candidates.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;

std::vector<Vector6d> Generate(const Robot& robot, CandidateKind kind, int count, uint64_t seed) {
  CandidateOptions options;
  options.kind = kind;
  options.count = count;
  options.seed = seed;
  return GenerateCandidates(robot, options)->poses;
}

class IoopsTest : public ::testing::Test {
 protected:
  // The boundary set costs 64 all-mode FK solves: computed once for the suite.
  static const std::vector<Vector6d>& Boundary() {
    static const std::vector<Vector6d> boundary =
        Generate(Preset("inria-left-hand"), CandidateKind::kBoundary, 0, 1);
    return boundary;
  }
  PlanningModel model_{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  const std::vector<Vector6d>& boundary_ = Boundary();
  std::vector<Vector6d> random18_ = Generate(model_.robot, CandidateKind::kRandom, 18, 77);
};

// Table 2: selected poses reach O2 = 0.0139; a plan from the 44 boundary poses must too,
// with every index far above the random start's.
TEST_F(IoopsTest, BoundaryPlanReachesThePapersO2) {
  ASSERT_EQ(boundary_.size(), 44u);
  PlannerOptions options;
  options.secondary = Criterion::kO4;
  options.tabu = 4;
  options.iterations = 150;
  StatusOr<PlanResult> plan = PlanPoses(model_, boundary_, random18_, options);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_GE(plan->final.o2, 0.0139);
  EXPECT_GT(plan->final.o1, 1.5 * plan->initial.o1);
  EXPECT_GT(plan->final.o2, 5 * plan->initial.o2);
  EXPECT_GT(plan->final.o3, 5 * plan->initial.o3);
  EXPECT_GT(plan->final.o4, 10 * plan->initial.o4);
  for (const Vector6d& pose : plan->poses) EXPECT_TRUE(model_.IsFeasible(pose));
}

// The screened secondary (bounds first, secular equations for few) makes the
// same choices as scoring every candidate on it: the same plan, pose for pose.
TEST_F(IoopsTest, ScreenedSecondaryChoosesAsThePlainScoring) {
  std::vector<Vector6d> candidates = Generate(model_.robot, CandidateKind::kRandom, 1500, 78);
  candidates.insert(candidates.end(), boundary_.begin(), boundary_.end());
  for (Criterion secondary : {Criterion::kO2, Criterion::kO3, Criterion::kO4, Criterion::kE}) {
    PlannerOptions options;
    options.secondary = secondary;
    options.tabu = 4;
    options.iterations = 40;
    StatusOr<PlanResult> screened = PlanPoses(model_, candidates, random18_, options);
    options.screen = false;
    StatusOr<PlanResult> plain = PlanPoses(model_, candidates, random18_, options);
    ASSERT_TRUE(screened.ok() && plain.ok());
    EXPECT_EQ(screened->poses, plain->poses) << CriterionName(secondary);
    EXPECT_EQ(screened->best_iteration, plain->best_iteration) << CriterionName(secondary);
  }
}

// S alone, screened by the quadratic-form bound (QuadraticFormCache), makes
// the same choices as scoring every candidate on it.
TEST_F(IoopsTest, ScreenedSigmaChoosesAsThePlainScoring) {
  std::vector<Vector6d> candidates = Generate(model_.robot, CandidateKind::kRandom, 3000, 79);
  candidates.insert(candidates.end(), boundary_.begin(), boundary_.end());
  PlannerOptions options;
  options.criterion = Criterion::kS;
  options.tabu = 4;
  options.iterations = 120;  // past four cache refreshes (every 25 exchanges)
  StatusOr<PlanResult> screened = PlanPoses(model_, candidates, random18_, options);
  options.screen = false;
  StatusOr<PlanResult> plain = PlanPoses(model_, candidates, random18_, options);
  ASSERT_TRUE(screened.ok() && plain.ok());
  EXPECT_EQ(screened->poses, plain->poses);
  EXPECT_EQ(screened->best_iteration, plain->best_iteration);
  EXPECT_EQ(screened->final_primary, plain->final_primary);
}

// A start drawn from the candidates themselves (a subset of measured poses):
// those poses are in the plan already and are never added a second time.
TEST_F(IoopsTest, StartFromCandidatesNeverRepeatsAPose) {
  const std::vector<Vector6d> measured = Generate(model_.robot, CandidateKind::kRandom, 30, 11);
  std::mt19937_64 rng(4);
  for (int draw = 0; draw < 12; ++draw) {
    std::vector<Vector6d> shuffled = measured;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    const std::vector<Vector6d> start(shuffled.begin(), shuffled.begin() + 9);
    for (Criterion criterion : {Criterion::kO1, Criterion::kO4}) {
      PlannerOptions options;
      options.num_poses = 9;
      options.criterion = criterion;
      StatusOr<PlanResult> plan = PlanPoses(model_, measured, start, options);
      if (!plan.ok()) continue;  // a start that does not identify every parameter
      for (const Vector6d& candidate : measured) {
        EXPECT_LE(std::count(plan->poses.begin(), plan->poses.end(), candidate), 1)
            << CriterionName(criterion) << ", draw " << draw;
      }
      // Every pose is a candidate, and says which.
      ASSERT_EQ(plan->candidate_indices.size(), plan->poses.size());
      for (size_t k = 0; k < plan->poses.size(); ++k) {
        ASSERT_GE(plan->candidate_indices[k], 0);
        EXPECT_EQ(measured[plan->candidate_indices[k]], plan->poses[k]);
      }
    }
  }
}

// DETMAX property: without Tabu, removing the pose just added is always possible, so the
// criterion never decreases; the run stops when that is the best removal.
TEST_F(IoopsTest, PlainIoopsNeverDecreasesAndConverges) {
  const std::vector<Vector6d> candidates = Generate(model_.robot, CandidateKind::kRandom, 1500, 3);
  PlannerOptions options;
  std::vector<PlanIteration> observed;  // the live feed must be the history, entry for entry
  std::vector<int> progress;
  JobHooks hooks;
  hooks.progress = [&](int iteration, int budget) {
    EXPECT_EQ(budget, options.IterationBudget());
    progress.push_back(iteration);
  };
  StatusOr<PlanResult> plan = PlanPoses(model_, candidates, random18_, options, hooks,
                                        [&](const PlanIteration& step) { observed.push_back(step); });
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  ASSERT_EQ(observed.size(), plan->history.size());
  double best = -1;
  for (size_t k = 0; k < observed.size(); ++k) {
    EXPECT_EQ(observed[k].iteration, plan->history[k].iteration);
    EXPECT_EQ(observed[k].indices.o2, plan->history[k].indices.o2);
    best = std::max(best, plan->history[k].primary);
    EXPECT_EQ(plan->history[k].best, best);  // without a secondary, the best primary so far
  }
  ASSERT_EQ(progress.size(), plan->history.size() - 1);
  for (size_t k = 0; k < progress.size(); ++k) EXPECT_EQ(progress[k], static_cast<int>(k) + 1);
  EXPECT_TRUE(plan->converged);
  for (size_t k = 1; k < plan->history.size(); ++k) {
    EXPECT_GE(plan->history[k].primary, plan->history[k - 1].primary * (1 - 1e-12)) << "iteration " << k;
  }
  EXPECT_FALSE(plan->history.back().exchanged);
  EXPECT_EQ(plan->poses.size(), 18u);
}

// With Tabu the search may degrade the current plan, but the one returned is the best seen.
TEST_F(IoopsTest, TabuReturnsTheBestPlanSeen) {
  PlannerOptions options;
  options.tabu = 4;
  options.iterations = 60;
  StatusOr<PlanResult> plan = PlanPoses(model_, boundary_, random18_, options);
  ASSERT_TRUE(plan.ok());
  double best = 0;
  for (const PlanIteration& step : plan->history) best = std::max(best, step.primary);
  EXPECT_NEAR(plan->final_primary, best, 1e-12 * best);
  EXPECT_EQ(plan->iterations, 60);
}

TEST_F(IoopsTest, SameSeedSamePlan) {
  PlannerOptions options;
  options.tabu = 3;
  options.iterations = 30;
  options.addfind_starts = 20;  // random subsets: the seed matters
  options.removal_choices = 2;
  const auto a = PlanPoses(model_, boundary_, random18_, options);
  const auto b = PlanPoses(model_, boundary_, random18_, options);
  ASSERT_TRUE(a.ok() && b.ok());
  for (size_t k = 0; k < a->poses.size(); ++k) EXPECT_EQ(a->poses[k], b->poses[k]);
}

// Rows given by the caller (shared with the certificates) plan as rows computed
// here; rows of another candidate count are refused.
TEST_F(IoopsTest, GivenRowsPlanAsComputedOnes) {
  PlannerOptions options;
  options.criterion = Criterion::kS;
  options.tabu = 2;
  options.iterations = 20;
  const CandidateRows rows = model_.RowsOf(boundary_);
  const auto given = PlanPoses(model_, boundary_, &rows, random18_, options);
  const auto computed = PlanPoses(model_, boundary_, random18_, options);
  ASSERT_TRUE(given.ok() && computed.ok());
  EXPECT_EQ(given->poses, computed->poses);
  EXPECT_EQ(given->final_primary, computed->final_primary);
  const std::vector<Vector6d> fewer(boundary_.begin(), boundary_.end() - 1);
  EXPECT_FALSE(PlanPoses(model_, fewer, &rows, random18_, options).ok());
}

// Continuous AddFind: SLSQP from random starts improves the plan and stays feasible.
TEST_F(IoopsTest, ContinuousSearchImprovesAndStaysFeasible) {
  const std::vector<Vector6d> starts = Generate(model_.robot, CandidateKind::kRandom, 200, 4);
  PlannerOptions options;
  options.continuous = true;
  options.addfind_starts = 6;
  options.iterations = 8;
  StatusOr<PlanResult> plan = PlanPoses(model_, starts, random18_, options);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_GT(plan->final.o1, 1.2 * plan->initial.o1);
  for (const Vector6d& pose : plan->poses) EXPECT_TRUE(model_.IsFeasible(pose));
}

// Without a pose-box bound on an angle, SLSQP winds it freely; planned poses
// give it back in [-180, 180] (without the fix this plan has a pose at q3 =
// 139604 degrees), still feasible.
TEST_F(IoopsTest, ContinuousSearchGivesFreeAnglesWithinAHalfTurn) {
  Robot robot = model_.robot;
  robot.limits.pose_box->bounds[5].reset();
  const PlanningModel free_yaw{robot, std::nullopt, std::nullopt};
  PlannerOptions options;
  options.criterion = Criterion::kS;
  options.continuous = true;
  options.addfind_starts = 12;
  options.iterations = 30;
  const std::vector<Vector6d> starts = Generate(robot, CandidateKind::kRandom, 300, 4);
  StatusOr<PlanResult> plan = PlanPoses(free_yaw, starts, random18_, options);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  for (const Vector6d& pose : plan->poses) {
    EXPECT_LE(std::abs(pose[5]), 180) << pose.transpose();
    EXPECT_TRUE(free_yaw.IsFeasible(pose));
  }
}

// Scores are computed in fixed blocks of candidates: the same on any number of threads.
TEST_F(IoopsTest, ScoresDoNotDependOnTheThreadCount) {
  const std::vector<Vector6d> candidates = Generate(model_.robot, CandidateKind::kRandom, 2500, 6);
  CandidateRows rows;
  rows.Resize(static_cast<int>(candidates.size()));
  for (size_t j = 0; j < candidates.size(); ++j) rows.Set(static_cast<int>(j), model_.Rows(candidates[j]));
  std::vector<PoseRows> plan;
  for (const Vector6d& pose : random18_) plan.push_back(model_.Rows(pose));
  const DesignState state = DesignState::FromRows(plan);
  for (Criterion criterion : {Criterion::kO1, Criterion::kA, Criterion::kO4}) {
    std::vector<double> one, three;
    ScoreInParallel(state, criterion, rows, &one, 1);
    ScoreInParallel(state, criterion, rows, &three, 3);
    EXPECT_EQ(one, three) << CriterionName(criterion);
  }
}

TEST_F(IoopsTest, ErrorsAndCancellation) {
  PlannerOptions options;
  options.num_poses = 6;
  EXPECT_FALSE(PlanPoses(model_, boundary_, std::vector<Vector6d>(random18_.begin(), random18_.begin() + 6), options).ok());
  options.num_poses = 18;
  const std::vector<Vector6d> same(18, random18_.front());
  StatusOr<PlanResult> singular = PlanPoses(model_, boundary_, same, options);
  ASSERT_FALSE(singular.ok());
  EXPECT_NE(singular.status().message().find("singular"), std::string::npos);
  std::atomic<bool> cancel{true};
  JobHooks hooks;
  hooks.cancel = &cancel;
  StatusOr<PlanResult> cancelled = PlanPoses(model_, boundary_, random18_, options, hooks);
  ASSERT_FALSE(cancelled.ok());
  EXPECT_TRUE(cancelled.status().cancelled());
}

// The rules between options name the option they refuse by its key, which
// the CLI shows as its flag and the GUI as its label.
TEST(PlannerOptionsCheck, RulesBetweenOptionsNameTheOption) {
  PlannerOptions options;
  options.num_poses = 12;
  EXPECT_TRUE(options.Check().ok());
  options.tabu = 12;
  Status s = options.Check();
  EXPECT_EQ(s.option(), "tabu");
  EXPECT_EQ(s.message(), "tabu: must be shorter than the plan (12 poses), got 12");
  options.tabu = 11;
  EXPECT_TRUE(options.Check().ok());
  options.criterion_switch_probability = 0.5;
  s = options.Check();
  EXPECT_EQ(s.option(), "switch_probability");
  options.secondary = Criterion::kO1;
  EXPECT_TRUE(options.Check().ok());
  options.removal_choices = 0;  // a range of PlannerOptionSpecs
  EXPECT_EQ(options.Check().option(), "removal_choices");
}

}  // namespace
}  // namespace hexcal

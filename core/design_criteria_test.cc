// Design criteria: every rank-one update against direct recomputation, the
// secular-equation eigenvalues against Eigen, the continuous-search gradient
// against finite differences, and the optimality certificate against the
// Kiefer–Wolfowitz equivalence theorem.
#include "core/design_criteria.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "core/candidates.h"
#include "core/continuous_addfind.h"
#include "core/quadratic_form_cache.h"
#include "core/observability.h"
#include "core/plan_certificate.h"
#include "core/planning_model.h"
#include "core/quadratic_form_cache.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::RandomFeasiblePoses;
using ::hexcal::testing::SpreadFeasiblePoses;
using ::hexcal::testing::Uniform;

constexpr Criterion kAll[] = {Criterion::kO1, Criterion::kO2, Criterion::kO3, Criterion::kO4,
                              Criterion::kD,  Criterion::kA,  Criterion::kE,  Criterion::kS};

// INRIA's planning model, its rows plain or weighted by the default noise model.
PlanningModel InriaModel(bool weighted) {
  PlanningModel model{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  if (weighted) model.noise = NoiseModel{};
  return model;
}

// The rows of every pose, in order: a plan for DesignState::FromRows.
std::vector<PoseRows> PlanRows(const PlanningModel& model, const std::vector<Vector6d>& poses) {
  std::vector<PoseRows> rows;
  for (const Vector6d& v : poses) rows.push_back(model.Rows(v));
  return rows;
}

// The candidates' rows, each from model.Rows (not RowsOf, whose threads these
// tests leave out of the comparison).
CandidateRows CandidateBatch(const PlanningModel& model, const std::vector<Vector6d>& candidates) {
  CandidateRows batch;
  batch.Resize(static_cast<int>(candidates.size()));
  for (size_t j = 0; j < candidates.size(); ++j) batch.Set(static_cast<int>(j), model.Rows(candidates[j]));
  return batch;
}

// O1..O4 from DesignState agree with observability.h (the paper's definitions).
TEST(DesignCriteria, ValuesAgreeWithObservabilityIndices) {
  const PlanningModel model{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  const std::vector<Vector6d> poses = SpreadFeasiblePoses(model.robot, 18, 3);
  std::vector<PoseRows> rows;
  std::vector<Pose> as_poses;
  for (const Vector6d& v : poses) {
    rows.push_back(model.Rows(v));
    as_poses.push_back(model.robot.PoseFromVector(v));
  }
  const DesignState state = DesignState::FromRows(rows);
  const ObservabilityIndices o = ComputeIndices(model.robot, as_poses);
  EXPECT_NEAR(state.Value(Criterion::kO1), o.o1, 1e-10 * o.o1);
  EXPECT_NEAR(state.Value(Criterion::kO2), o.o2, 1e-7 * o.o2);
  EXPECT_NEAR(state.Value(Criterion::kO3), o.o3, 1e-7 * o.o3);
  EXPECT_NEAR(state.Value(Criterion::kO4), o.o4, 1e-7 * o.o4);
  EXPECT_NEAR(state.Value(Criterion::kE), o.sigma_min * o.sigma_min, 1e-7 * o.sigma_min * o.sigma_min);
  // S from the whole 42 x 42 information matrix, inverted densely (no per-leg blocks).
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(kNumParams, kNumParams);
  for (const PoseRows& pose_rows : rows) {
    for (int i = 0; i < kNumLegs; ++i) {
      Eigen::VectorXd full = Eigen::VectorXd::Zero(kNumParams);
      full.segment<kParamsPerLeg>(kParamsPerLeg * i) = pose_rows[i].transpose();
      information += full * full.transpose();
    }
  }
  const Eigen::VectorXd variances = information.inverse().diagonal();
  const double mean_sigma = variances.cwiseSqrt().mean();
  EXPECT_NEAR(state.Value(Criterion::kS), 1 / mean_sigma, 1e-8 / mean_sigma);
}

// The batch scores (determinant lemma, Sherman–Morrison, secular equation) equal a
// from-scratch evaluation of the set plus each candidate.
TEST(DesignCriteria, IncrementalScoresMatchRecomputation) {
  for (bool weighted : {false, true}) {
    const PlanningModel model = InriaModel(weighted);
    const std::vector<PoseRows> rows = PlanRows(model, SpreadFeasiblePoses(model.robot, 18, 5));
    const std::vector<Vector6d> candidates = SpreadFeasiblePoses(model.robot, 200, 6);
    const DesignState state = DesignState::FromRows(rows);
    const CandidateRows batch = CandidateBatch(model, candidates);
    for (Criterion criterion : kAll) {
      std::vector<double> scores(candidates.size());
      state.ScoreAdditions(criterion, batch, 0, batch.size(), scores.data());
      for (size_t j = 0; j < candidates.size(); j += 17) {
        std::vector<PoseRows> plus = rows;
        plus.push_back(batch.Rows(static_cast<int>(j)));
        const double direct = DesignState::FromRows(plus).Value(criterion);
        EXPECT_NEAR(scores[j], direct, 1e-8 * std::abs(direct)) << CriterionName(criterion) << " candidate " << j;
      }
    }
  }
}

// Removing a pose evaluates S without eigendecompositions: bit for bit the
// value of a state built from the downdated blocks, down to a plan left
// rank-deficient (0), and that of the remaining poses up to rounding.
TEST(DesignCriteria, ValueAfterRemovingIsTheRecomputedValue) {
  PlanningModel model{Preset("inria-left-hand"), NoiseModel{}, std::nullopt};
  for (int size : {7, 8, 18}) {
    const std::vector<PoseRows> rows = PlanRows(model, SpreadFeasiblePoses(model.robot, size, 7));
    const DesignState state = DesignState::FromRows(rows);
    for (size_t k = 0; k < rows.size(); ++k) {
      std::array<InfoBlock, kNumLegs> downdated = state.blocks();
      for (int i = 0; i < kNumLegs; ++i) downdated[i].noalias() -= rows[k][i].transpose() * rows[k][i];
      std::vector<PoseRows> rest = rows;
      rest.erase(rest.begin() + static_cast<long>(k));
      const double value = state.ValueAfterRemoving(Criterion::kS, rows[k]);
      EXPECT_EQ(value, DesignState(downdated, size - 1).Value(Criterion::kS)) << size << " poses less pose " << k;
      // The downdate itself rounds: a nearly singular plan's σ lose a few digits.
      const double direct = DesignState::FromRows(rest).Value(Criterion::kS);
      EXPECT_NEAR(value, direct, 1e-6 * direct) << size << " poses less pose " << k;
    }
  }
}

// With a noise model the row Jacobian is central differences of Rows; its x,
// y and z columns reuse the pose's rotation partials and must still be those
// differences bit for bit.
TEST(DesignCriteria, RowJacobiansAreTheCentralDifferencesOfRows) {
  const PlanningModel model{Preset("inria-left-hand"), NoiseModel{}, std::nullopt};
  for (const Vector6d& v : SpreadFeasiblePoses(model.robot, 20, 9)) {
    const auto jacobians = model.RowJacobians(v);
    for (int k = 0; k < 6; ++k) {
      const double h = 1e-6 * (1 + std::abs(v[k]));
      Vector6d plus = v, minus = v;
      plus[k] += h;
      minus[k] -= h;
      const PoseRows up = model.Rows(plus), down = model.Rows(minus);
      for (int i = 0; i < kNumLegs; ++i) {
        const JacobianRow difference = (up[i] - down[i]) / (2 * h);
        EXPECT_EQ(jacobians[i].col(k).transpose(), difference) << "leg " << i << ", coordinate " << k;
      }
    }
  }
}

// The screening bounds of the eigenvalue criteria are never below the exact
// values, for every candidate, and they rank: the best bound's candidate is
// within a few per cent of the best value.
TEST(DesignCriteria, UpperBoundsAreAboveTheExactScores) {
  for (bool weighted : {false, true}) {
    const PlanningModel model = InriaModel(weighted);
    const DesignState state = DesignState::FromRows(PlanRows(model, SpreadFeasiblePoses(model.robot, 18, 21)));
    const CandidateRows batch = CandidateBatch(model, SpreadFeasiblePoses(model.robot, 500, 22));
    for (Criterion criterion : {Criterion::kO2, Criterion::kO3, Criterion::kO4, Criterion::kE}) {
      ASSERT_TRUE(IsEigenvalueCriterion(criterion));
      std::vector<double> exact(batch.size()), bound(batch.size());
      state.ScoreAdditions(criterion, batch, 0, batch.size(), exact.data());
      state.ScoreUpperBounds(criterion, batch, 0, batch.size(), bound.data());
      for (int j = 0; j < batch.size(); ++j) {
        EXPECT_GE(bound[j], exact[j]) << CriterionName(criterion) << " weighted " << weighted << " candidate " << j;
      }
    }
  }
  EXPECT_FALSE(IsEigenvalueCriterion(Criterion::kS));
  EXPECT_FALSE(IsEigenvalueCriterion(Criterion::kO1));
}

// Secular-equation extremes of diag(λ) + z zᵀ against a dense eigen-solve, including
// deflated (z_k = 0) and repeated eigenvalues.
TEST(DesignCriteria, SecularExtremesMatchDenseEigenvalues) {
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::Matrix<double, 7, 1> lambda, z;
    for (int k = 0; k < 7; ++k) {
      lambda[k] = std::pow(10.0, Uniform(-2, 6));
      z[k] = Uniform(-30, 30);
    }
    if (trial % 5 == 1) z[0] = 0;
    if (trial % 7 == 2) lambda[1] = lambda[0];
    std::sort(lambda.data(), lambda.data() + 7);
    double smallest, largest;
    RankOneExtremeEigenvalues(lambda, z, &smallest, &largest);
    const Eigen::Matrix<double, 7, 7> dense = Eigen::Matrix<double, 7, 7>(lambda.asDiagonal()) + z * z.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 7, 7>> solver(dense);
    const Eigen::Matrix<double, 7, 1> exact = solver.eigenvalues();
    EXPECT_NEAR(smallest, exact[0], 1e-9 * exact[6]) << "trial " << trial;
    EXPECT_NEAR(largest, exact[6], 1e-9 * exact[6]) << "trial " << trial;
  }
}

// The analytic criterion gradient used by SLSQP against central differences.
TEST(DesignCriteria, ContinuousGradientMatchesFiniteDifferences) {
  for (bool weighted : {false, true}) {
    const PlanningModel model = InriaModel(weighted);
    const DesignState state = DesignState::FromRows(PlanRows(model, SpreadFeasiblePoses(model.robot, 12, 9)));
    const Vector6d pose = SpreadFeasiblePoses(model.robot, 1, 10).front();
    for (Criterion criterion : kAll) {
      Vector6d gradient, unused;
      CriterionAndGradient(model, state, criterion, pose, &gradient);
      // Reference: Richardson-extrapolated central differences. The eigenvalue criteria
      // need a larger step: λ_min (~1) is computed next to λ_max (~1e6), so a step of
      // h carries a round-off of about ε λ_max / h in the difference quotient.
      auto central = [&](int k, double h) {
        Vector6d plus = pose, minus = pose;
        plus[k] += h;
        minus[k] -= h;
        return (CriterionAndGradient(model, state, criterion, plus, &unused) -
                CriterionAndGradient(model, state, criterion, minus, &unused)) / (2 * h);
      };
      for (int k = 0; k < 6; ++k) {
        const bool smooth = criterion == Criterion::kO1 || criterion == Criterion::kD || criterion == Criterion::kA ||
                            criterion == Criterion::kS;
        const double h = smooth ? 1e-5 : 1e-3;
        const double numeric = (4 * central(k, h) - central(k, 2 * h)) / 3;
        EXPECT_NEAR(gradient[k], numeric, 1e-5 * (std::abs(numeric) + 1e-3 * gradient.cwiseAbs().maxCoeff()))
            << CriterionName(criterion) << " weighted " << weighted << " k " << k;
      }
    }
  }
}

// Kiefer–Wolfowitz: at the D-optimal design the variance function's maximum is p = 42,
// attained on the support; and the certified efficiency of any plan is at most 1.
TEST(OptimalDesign, SatisfiesTheEquivalenceTheorem) {
  const PlanningModel model{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  CandidateOptions options;
  options.kind = CandidateKind::kBoundary;
  std::vector<Vector6d> candidates = GenerateCandidates(model.robot, options)->poses;
  const std::vector<Vector6d> random = SpreadFeasiblePoses(model.robot, 150, 12);
  candidates.insert(candidates.end(), random.begin(), random.end());
  const CandidateRows rows = CandidateBatch(model, candidates);
  StatusOr<OptimalDesign> design = ComputeOptimalDesign(rows);
  ASSERT_TRUE(design.ok()) << design.status().message();
  EXPECT_TRUE(design->converged) << "gap " << design->gap << " after " << design->iterations;
  EXPECT_NEAR(design->max_variance, kNumParams, kNumParams * 1e-4);
  // Independent check of d(x, w) from the weights alone.
  std::array<InfoBlock, kNumLegs> inverses;
  for (int i = 0; i < kNumLegs; ++i) {
    InfoBlock m = InfoBlock::Zero();
    for (int j = 0; j < rows.size(); ++j) m += design->weights[j] * rows.legs[i].col(j) * rows.legs[i].col(j).transpose();
    inverses[i] = m.inverse();
  }
  Eigen::ArrayXd d;
  VarianceFunction(inverses, rows, &d);
  EXPECT_NEAR(d.maxCoeff(), kNumParams, kNumParams * 1e-4);
  for (int j = 0; j < rows.size(); ++j) {
    if (design->weights[j] > 1e-3) {
      EXPECT_NEAR(d[j], kNumParams, 0.01 * kNumParams) << "support point " << j;
    }
  }
  const std::vector<Vector6d> plan = SpreadFeasiblePoses(model.robot, 18, 13);
  StatusOr<PlanCertificate> random_plan = CertifyPlan(model, candidates, plan);
  ASSERT_TRUE(random_plan.ok());
  EXPECT_GT(random_plan->d_efficiency, 0);
  EXPECT_LE(random_plan->d_efficiency, 1);
  // The planner's rows of a prefix of the candidates, reused: the same certificate.
  const CandidateRows prefix = model.RowsOf(std::vector<Vector6d>(candidates.begin(), candidates.end() - 5));
  StatusOr<PlanCertificate> reused = CertifyPlan(model, candidates, plan, {}, &prefix);
  ASSERT_TRUE(reused.ok());
  EXPECT_EQ(reused->d_efficiency, random_plan->d_efficiency);
  EXPECT_EQ(reused->s_efficiency, random_plan->s_efficiency);
  EXPECT_EQ(reused->design.weights, random_plan->design.weights);
}

// The variance function is computed in fixed blocks of candidates spread over
// the threads: the design is the same, bit for bit, on any number of threads.
TEST(OptimalDesign, DoesNotDependOnTheThreadCount) {
  const PlanningModel model{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  const std::vector<Vector6d> candidates = SpreadFeasiblePoses(model.robot, 2500, 5);
  const CandidateRows rows = CandidateBatch(model, candidates);
  OptimalDesignOptions options;
  options.max_iterations = 20;
  options.threads = 1;
  StatusOr<OptimalDesign> one = ComputeOptimalDesign(rows, options);
  options.threads = 3;
  StatusOr<OptimalDesign> three = ComputeOptimalDesign(rows, options);
  ASSERT_TRUE(one.ok() && three.ok());
  EXPECT_EQ(one->weights, three->weights);
  EXPECT_EQ(one->log_det, three->log_det);
  EXPECT_EQ(one->max_variance, three->max_variance);
}

}  // namespace
}  // namespace hexcal

namespace hexcal {
namespace {

// The rows of the first `count` poses: a plan.
std::vector<PoseRows> FirstRows(const PlanningModel& model, const std::vector<Vector6d>& poses, int count) {
  return PlanRows(model, std::vector<Vector6d>(poses.begin(), poses.begin() + count));
}

// The Sherman–Morrison-maintained quadratic forms equal fresh ones after a series
// of exchanges, and their growth ranks candidates exactly as O1 does; they
// bound S from above.
TEST(QuadraticFormCache, TracksExchangesExactly) {
  const PlanningModel model{Preset("inria-left-hand"), std::nullopt, std::nullopt};
  const std::vector<Vector6d> poses = RandomFeasiblePoses(model.robot, 300, 21);
  std::vector<PoseRows> plan = FirstRows(model, poses, 18);
  CandidateRows candidates;
  candidates.Resize(200);
  for (int j = 0; j < 200; ++j) candidates.Set(j, model.Rows(poses[100 + j]));
  DesignState state = DesignState::FromRows(plan);
  QuadraticFormCache cache;
  cache.Reset(state, candidates);
  for (int step = 0; step < 30; ++step) {
    const PoseRows added = candidates.Rows(step * 5);
    const PoseRows removed = plan[step % plan.size()];
    const DesignState before = state;
    state.Add(added);
    if (step % 2 == 0) {  // both update paths: separate and fused
      cache.Added(before, candidates, added);
      cache.Removed(state, candidates, removed);
    } else {
      cache.Exchanged(before, added, state, removed, candidates);
    }
    state.Remove(removed);
    plan[step % plan.size()] = added;
  }
  std::vector<double> growth, scores(200);
  cache.Growth(&growth);
  state.ScoreAdditions(Criterion::kO1, candidates, 0, 200, scores.data());
  for (int j = 0; j < 200; ++j) {
    // O1 = exp((log det M + log growth) / 84) / sqrt(N + 1)
    const double o1 = std::exp((std::log(std::pow(state.Value(Criterion::kD), kNumParams)) + std::log(growth[j])) /
                               (2.0 * kNumParams)) / std::sqrt(19.0);
    EXPECT_NEAR(o1, scores[j], 1e-9 * scores[j]) << "candidate " << j;
  }

  // The same forms bound S from above: never below its exact value, and equal
  // to it only when u is parallel to every unit vector (never, with 7 parameters).
  std::vector<double> bounds;
  cache.SigmaUpperBounds(state, &bounds);
  state.ScoreAdditions(Criterion::kS, candidates, 0, 200, scores.data());
  for (int j = 0; j < 200; ++j) {
    EXPECT_GE(bounds[j], scores[j]) << "candidate " << j;
    EXPECT_GT(bounds[j], state.Value(Criterion::kS)) << "candidate " << j;
  }
}

// Rows kept as float (the S search's cache) still bound S from above, on
// noise-weighted rows as the planner's, on both presets; rounding the rows
// moves a bound by a tenth of its slack (1e-4) at most (1.0e-6 on INRIA's
// rows, 1.0e-7 on DeltaLab's).
TEST(QuadraticFormCache, SinglePrecisionStillBoundsS) {
  for (const char* name : {"inria-left-hand", "deltalab-table"}) {
    const PlanningModel model{Preset(name), NoiseModel{}, std::nullopt};
    const std::vector<Vector6d> poses = RandomFeasiblePoses(model.robot, 2300, 22);
    std::vector<PoseRows> plan = FirstRows(model, poses, 18);
    const CandidateRows candidates = model.RowsOf(std::vector<Vector6d>(poses.begin() + 300, poses.end()));
    const int count = candidates.size();
    DesignState state = DesignState::FromRows(plan);
    QuadraticFormCache single, exact;
    single.Reset(state, candidates, 0, /*single_precision=*/true);
    exact.Reset(state, candidates);
    for (int step = 0; step < 40; ++step) {
      const PoseRows added = candidates.Rows(step * 37), removed = plan[step % plan.size()];
      const DesignState before = state;
      state.Add(added);
      single.Exchanged(before, added, state, removed, candidates);
      exact.Exchanged(before, added, state, removed, candidates);
      state.Remove(removed);
      plan[step % plan.size()] = added;
    }
    std::vector<double> bounds, exact_bounds, scores(count);
    single.SigmaUpperBounds(state, &bounds);
    exact.SigmaUpperBounds(state, &exact_bounds);
    state.ScoreAdditions(Criterion::kS, candidates, 0, count, scores.data());
    for (int j = 0; j < count; ++j) {
      EXPECT_GE(bounds[j], scores[j]) << name << " candidate " << j;
      // The slacks are 1e-4 and 1e-9: what is left is the rounding's.
      const double rounding = bounds[j] / (1 + 1e-4) / (exact_bounds[j] / (1 + 1e-9)) - 1;
      EXPECT_LT(std::abs(rounding), 1e-5) << name << " candidate " << j;
    }
  }
}

constexpr double kCrowding = 0.1;  // robot unit and degrees

// Seven poses crowded together make an ill-conditioned plan: rounding the
// rows would move the bounds by more than a tenth of their slack, so the cache
// keeps them double; a spread plan keeps them float.
TEST(QuadraticFormCache, KeepsDoubleRowsWhenRoundingMatters) {
  const PlanningModel model{Preset("inria-left-hand"), NoiseModel{}, std::nullopt};
  const std::vector<Vector6d> poses = RandomFeasiblePoses(model.robot, 1300, 23);
  const CandidateRows candidates = model.RowsOf(std::vector<Vector6d>(poses.begin() + 300, poses.end()));
  QuadraticFormCache cache;
  cache.Reset(DesignState::FromRows(FirstRows(model, poses, 18)), candidates, 0, /*single_precision=*/true);
  EXPECT_TRUE(cache.single_precision());
  std::vector<PoseRows> crowded;
  for (int k = 0; k < kParamsPerLeg; ++k) {
    Vector6d v = poses[0];
    v[k % 6] += kCrowding * (k + 1);
    crowded.push_back(model.Rows(v));
  }
  const DesignState state = DesignState::FromRows(crowded);
  ASSERT_TRUE(state.full_rank());
  cache.Reset(state, candidates, 0, /*single_precision=*/true);
  EXPECT_FALSE(cache.single_precision());
}

}  // namespace
}  // namespace hexcal

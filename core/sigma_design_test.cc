// The S criterion's approximate design (sigma_design.h) against what its
// theory says independently of the solver: at the optimum no move of weight
// towards any candidate lowers Φ (checked by finite steps on Φ computed from
// dense inverses), the bound is below Φ(w), and exact plans are no better
// than the bound allows.
#include "core/sigma_design.h"

#include <gtest/gtest.h>

#include <limits>
#include <utility>

#include "core/planning_model.h"
#include "core/sigma_criterion.h"
#include "tests/robot_presets.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::SpreadFeasiblePoses;

struct Problem {
  PlanningModel model;
  std::vector<Vector6d> poses;
  CandidateRows rows;
};

// Spread candidates, as the boundary set would give, without its seconds of homotopy FK.
const std::vector<Vector6d>& SpreadPoses(const Robot& robot) {
  static const std::vector<Vector6d> poses = SpreadFeasiblePoses(robot, 300, 4);
  return poses;
}

Problem SpreadCandidates(bool weighted) {
  Problem p{{Preset("inria-left-hand"), std::nullopt, std::nullopt}, {}, {}};
  if (weighted) p.model.noise = NoiseModel{};
  p.poses = SpreadPoses(p.model.robot);
  p.rows.Resize(static_cast<int>(p.poses.size()));
  for (size_t j = 0; j < p.poses.size(); ++j) p.rows.Set(static_cast<int>(j), p.model.Rows(p.poses[j]));
  return p;
}

// Φ(w) from dense inverses of M_i(w), independent of the solver's factorisations.
double DensePhi(const CandidateRows& rows, const Eigen::ArrayXd& w) {
  const std::array<InfoBlock, kNumLegs> blocks = DesignInformation(rows, w);
  double sum = 0;
  for (const InfoBlock& block : blocks) sum += SigmaSum(block.inverse());
  return sum;
}

TEST(SigmaDesign, NoMoveTowardsACandidateImprovesTheOptimum) {
  for (bool weighted : {false, true}) {
    const Problem p = SpreadCandidates(weighted);
    StatusOr<SigmaDesign> design = ComputeSigmaOptimalDesign(p.rows);
    ASSERT_TRUE(design.ok()) << design.status().message();
    EXPECT_TRUE(design->converged) << "gap " << design->gap << " after " << design->iterations;
    const Eigen::ArrayXd w = Eigen::Map<const Eigen::ArrayXd>(design->weights.data(), design->weights.size());
    EXPECT_NEAR(w.sum(), 1, 1e-12);
    const double phi = DensePhi(p.rows, w);
    EXPECT_NEAR(phi, design->sigma_sum, 1e-9 * phi);
    // Directional derivative (Φ - d) / 2 >= -gap Φ / 2 in every direction: a
    // step of α towards candidate j changes Φ by at least -α gap Φ / 2 + O(α²).
    constexpr double kAlpha = 1e-4;
    for (int j = 0; j < p.rows.size(); j += 7) {
      Eigen::ArrayXd moved = (1 - kAlpha) * w;
      moved[j] += kAlpha;
      EXPECT_GE(DensePhi(p.rows, moved) - phi, -kAlpha * phi * (design->gap + 1e-3)) << "candidate " << j;
    }
    EXPECT_LE(design->SigmaSumBound(), phi);
    EXPECT_GE(design->SigmaSumBound(), phi * (1 - design->gap));
  }
}

// The exchange's Woodbury form against Φ from dense inverses of the moved weights.
TEST(SigmaDesign, SigmaSumAlongAnExchangeIsPhiOfTheMovedWeights) {
  const Problem p = SpreadCandidates(true);
  const int count = p.rows.size();
  Eigen::ArrayXd w = Eigen::ArrayXd::LinSpaced(count, 1, 2);
  w /= w.sum();
  const std::array<InfoBlock, kNumLegs> blocks = DesignInformation(p.rows, w);
  for (const auto& [to, from] : {std::pair{3, 17}, std::pair{120, 4}, std::pair{250, 251}}) {
    const SigmaSumAlongExchange phi(blocks, p.rows, to, from);
    for (double fraction : {0.0, 0.1, 0.5, 1.0}) {
      const double delta = fraction * w[from];
      Eigen::ArrayXd moved = w;
      moved[to] += delta;
      moved[from] -= delta;
      const double dense = DensePhi(p.rows, moved);
      EXPECT_NEAR(phi(delta), dense, 1e-10 * dense) << to << " <- " << from << ", δ = " << delta;
    }
    // Far past the support point's weight, M_i(δ) loses r_from's direction.
    EXPECT_EQ(phi(1e9), std::numeric_limits<double>::infinity());
  }
}

TEST(SigmaDesign, ExactPlansAreNoBetterThanTheBound) {
  const Problem p = SpreadCandidates(true);
  StatusOr<SigmaDesign> design = ComputeSigmaOptimalDesign(p.rows);
  ASSERT_TRUE(design.ok());
  // Any N candidates, as an exact design, have Σσ √N >= Φ* >= the bound.
  for (int first = 0; first + 18 <= p.rows.size(); first += 40) {
    std::vector<PoseRows> plan;
    for (int j = first; j < first + 18; ++j) plan.push_back(p.rows.Rows(j));
    const DesignState state = DesignState::FromRows(plan);
    if (!state.full_rank()) continue;
    const double efficiency = SEfficiencyLowerBound(state.blocks(), 18, *design);
    EXPECT_GT(efficiency, 0);
    EXPECT_LE(efficiency, 1) << "plan from candidate " << first;
  }
}

// Above 2 048 candidates the designs are solved on a working set: their
// optimality is still over every candidate, checked independently (dense
// inverses, the variance function and finite steps towards candidates).
TEST(SigmaDesign, WorkingSetDesignsAreOptimalOverEveryCandidate) {
  const Robot robot = Preset("inria-left-hand");
  const std::vector<Vector6d> poses = SpreadFeasiblePoses(robot, 4000, 8);
  PlanningModel model{robot, NoiseModel{}, std::nullopt};
  CandidateRows rows;
  rows.Resize(static_cast<int>(poses.size()));
  for (size_t j = 0; j < poses.size(); ++j) rows.Set(static_cast<int>(j), model.Rows(poses[j]));

  StatusOr<OptimalDesign> d_design = ComputeOptimalDesign(rows);
  ASSERT_TRUE(d_design.ok() && d_design->converged);
  ASSERT_EQ(d_design->weights.size(), poses.size());
  const Eigen::ArrayXd wd = Eigen::Map<const Eigen::ArrayXd>(d_design->weights.data(), d_design->weights.size());
  std::array<InfoBlock, kNumLegs> inverses = DesignInformation(rows, wd);
  for (InfoBlock& block : inverses) block = block.inverse().eval();
  Eigen::ArrayXd variance;
  VarianceFunction(inverses, rows, &variance);
  EXPECT_LT(variance.maxCoeff(), kNumParams * (1 + 1e-4));

  StatusOr<SigmaDesign> s_design = ComputeSigmaOptimalDesign(rows);
  ASSERT_TRUE(s_design.ok() && s_design->converged);
  const Eigen::ArrayXd w = Eigen::Map<const Eigen::ArrayXd>(s_design->weights.data(), s_design->weights.size());
  EXPECT_NEAR(w.sum(), 1, 1e-12);
  const double phi = DensePhi(rows, w);
  EXPECT_NEAR(phi, s_design->sigma_sum, 1e-9 * phi);
  constexpr double kAlpha = 1e-4;
  for (int j = 0; j < rows.size(); j += 13) {
    Eigen::ArrayXd moved = (1 - kAlpha) * w;
    moved[j] += kAlpha;
    EXPECT_GE(DensePhi(rows, moved) - phi, -kAlpha * phi * (s_design->gap + 1e-3)) << "candidate " << j;
  }
}

TEST(SigmaDesign, DoesNotDependOnTheThreadCount) {
  const Problem p = SpreadCandidates(false);
  OptimalDesignOptions options;
  options.max_iterations = 30;
  options.threads = 1;
  StatusOr<SigmaDesign> one = ComputeSigmaOptimalDesign(p.rows, options);
  options.threads = 3;
  StatusOr<SigmaDesign> three = ComputeSigmaOptimalDesign(p.rows, options);
  ASSERT_TRUE(one.ok() && three.ok());
  EXPECT_EQ(one->weights, three->weights);
}

}  // namespace
}  // namespace hexcal

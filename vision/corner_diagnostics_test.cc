#include "vision/corner_diagnostics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hexcal {
namespace {

CornerResidual At(double x, double y, double dx, double dy, int tag = 0) {
  CornerResidual c;
  c.tag_id = tag;
  c.observed = {x, y};
  c.residual = {dx, dy};
  return c;
}

// Residuals of the given lengths, each along a different direction.
std::vector<CornerResidual> OfLengths(const std::vector<double>& lengths) {
  std::vector<CornerResidual> corners;
  for (size_t i = 0; i < lengths.size(); ++i) {
    const double angle = 0.7 * static_cast<double>(i);
    corners.push_back(At(0, 0, lengths[i] * std::cos(angle), lengths[i] * std::sin(angle), static_cast<int>(i)));
  }
  return corners;
}

TEST(CornerDiagnosticsTest, WorstCornersAreTheLargestFirstWithTiesInInputOrder) {
  const std::vector<CornerResidual> corners = OfLengths({0.1, 3, 0.5, 3, 2});
  const std::vector<CornerResidual> worst = WorstCorners(corners, 3);
  ASSERT_EQ(worst.size(), 3u);
  EXPECT_EQ(worst[0].tag_id, 1);
  EXPECT_EQ(worst[1].tag_id, 3);
  EXPECT_EQ(worst[2].tag_id, 4);
  EXPECT_NEAR(worst[2].residual.norm(), 2, 1e-12);
  EXPECT_EQ(WorstCorners(corners, 10).size(), 5u);
  EXPECT_EQ(WorstCorners(corners, 10).back().tag_id, 0);
  EXPECT_TRUE(WorstCorners(corners, 0).empty());
}

TEST(CornerDiagnosticsTest, RobustSigmaIsTheRayleighMedianOverItsFactor) {
  // Median 2 (odd count), 2.5 (even count: the mean of 2 and 3).
  EXPECT_NEAR(RobustAxisSigma(OfLengths({1, 2, 30})), 2 / std::sqrt(2 * std::log(2.0)), 1e-12);
  EXPECT_NEAR(RobustAxisSigma(OfLengths({1, 2, 3, 40})), 2.5 / std::sqrt(2 * std::log(2.0)), 1e-12);
  EXPECT_EQ(RobustAxisSigma({}), 0);
  // Gaussian residuals of σ = 0.3 per axis give σ back, and 2 % of outliers hardly move it.
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0, 0.3);
  std::vector<CornerResidual> corners;
  for (int i = 0; i < 20000; ++i) corners.push_back(At(0, 0, noise(random), noise(random)));
  EXPECT_NEAR(RobustAxisSigma(corners), 0.3, 0.006);
  for (int i = 0; i < 400; ++i) corners.push_back(At(0, 0, 30, 0));
  EXPECT_NEAR(RobustAxisSigma(corners), 0.3, 0.012);
}

TEST(CornerDiagnosticsTest, HistogramBinsAreHalfOpenWithTheRestBeyond) {
  // σ = 1: bins of 0.25 px, 24 of them up to 6 px.
  const ResidualHistogram h = HistogramOfResiduals(OfLengths({0.1, 0.25, 0.3, 5.99, 6.0, 100}), 1.0);
  ASSERT_EQ(h.counts.size(), 24u);
  EXPECT_DOUBLE_EQ(h.bin_width, 0.25);
  EXPECT_EQ(h.counts[0], 1);
  EXPECT_EQ(h.counts[1], 2);
  EXPECT_EQ(h.counts[23], 1);
  EXPECT_EQ(h.beyond, 2);
  int total = h.beyond;
  for (int c : h.counts) total += c;
  EXPECT_EQ(total, 6);
  // Rayleigh: 6 (1 − exp(−0.25²/2)) in the first bin; all bins and beyond add up to 6.
  EXPECT_NEAR(h.expected[0], 6 * (1 - std::exp(-0.03125)), 1e-12);
  double expected = h.expected_beyond;
  for (double e : h.expected) expected += e;
  EXPECT_NEAR(expected, 6, 1e-9);
  EXPECT_NEAR(h.expected_beyond, 6 * std::exp(-18.0), 1e-12);
}

TEST(CornerDiagnosticsTest, GaussianResidualsFillTheHistogramAsRayleighExpects) {
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0, 0.2);
  std::vector<CornerResidual> corners;
  for (int i = 0; i < 40000; ++i) corners.push_back(At(0, 0, noise(random), noise(random)));
  const ResidualHistogram h = HistogramOfResiduals(corners, 0.2);
  for (size_t b = 0; b < h.counts.size(); ++b) {
    // Poisson counts: within 4 standard deviations (and 3 corners where almost none are expected).
    EXPECT_NEAR(h.counts[b], h.expected[b], 4 * std::sqrt(h.expected[b]) + 3) << "bin " << b;
  }
  // The mode of the Rayleigh density is σ: bin 3 or 4 ([0.75σ, 1.25σ)).
  const auto mode = std::max_element(h.counts.begin(), h.counts.end()) - h.counts.begin();
  EXPECT_TRUE(mode == 3 || mode == 4) << mode;
}

TEST(CornerDiagnosticsTest, CoverageCountsCornersPerCellAndClampsOutsiders) {
  // 640 × 480 in 8 × 6 cells of 80 × 80 pixels.
  const std::vector<CornerResidual> corners = {At(0, 0, 0, 0),         At(79.9, 0, 0, 0), At(80, 0, 0, 0),
                                               At(639.9, 479.9, 0, 0), At(700, -5, 0, 0), At(320, 240, 0, 0),
                                               At(319.9, 239.9, 0, 0)};
  const CoverageGrid grid = CountCorners(corners, 640, 480);
  ASSERT_EQ(grid.counts.size(), 48u);
  EXPECT_EQ(grid.At(0, 0), 2);
  EXPECT_EQ(grid.At(0, 1), 1);
  EXPECT_EQ(grid.At(5, 7), 1);
  EXPECT_EQ(grid.At(0, 7), 1);
  EXPECT_EQ(grid.At(3, 4), 1);
  EXPECT_EQ(grid.At(2, 3), 1);
  EXPECT_EQ(grid.EmptyCells(), 48 - 6);
  EXPECT_EQ(CountCorners({}, 640, 480, 4, 3).EmptyCells(), 12);
}

}  // namespace
}  // namespace hexcal

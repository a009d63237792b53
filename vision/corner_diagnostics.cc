#include "vision/corner_diagnostics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace hexcal {

std::vector<CornerResidual> WorstCorners(const std::vector<CornerResidual>& corners, int k) {
  std::vector<size_t> order(corners.size());
  std::iota(order.begin(), order.end(), 0);
  const size_t keep = std::min(order.size(), static_cast<size_t>(std::max(0, k)));
  std::partial_sort(order.begin(), order.begin() + keep, order.end(), [&](size_t a, size_t b) {
    const double na = corners[a].residual.squaredNorm(), nb = corners[b].residual.squaredNorm();
    return na != nb ? na > nb : a < b;
  });
  std::vector<CornerResidual> worst;
  for (size_t i = 0; i < keep; ++i) worst.push_back(corners[order[i]]);
  return worst;
}

double RobustAxisSigma(const std::vector<CornerResidual>& corners) {
  if (corners.empty()) return 0;
  std::vector<double> norms;
  for (const CornerResidual& c : corners) norms.push_back(c.residual.norm());
  const size_t middle = norms.size() / 2;
  std::nth_element(norms.begin(), norms.begin() + middle, norms.end());
  double median = norms[middle];
  if (norms.size() % 2 == 0) median = 0.5 * (median + *std::max_element(norms.begin(), norms.begin() + middle));
  return median / std::sqrt(2 * std::log(2.0));
}

double RayleighFraction(double a, double b, double sigma) {
  const double s2 = 2 * sigma * sigma;
  return std::exp(-a * a / s2) - (std::isinf(b) ? 0.0 : std::exp(-b * b / s2));
}

ResidualHistogram HistogramOfResiduals(const std::vector<CornerResidual>& corners, double sigma, int bins) {
  assert(sigma > 0 && bins > 0);
  ResidualHistogram h;
  h.sigma = sigma;
  h.bin_width = 6 * sigma / bins;
  h.counts.assign(static_cast<size_t>(bins), 0);
  for (const CornerResidual& c : corners) {
    const double bin = std::floor(c.residual.norm() / h.bin_width);
    if (bin >= bins) {
      ++h.beyond;
    } else {
      ++h.counts[static_cast<size_t>(bin)];
    }
  }
  const double n = static_cast<double>(corners.size());
  for (int b = 0; b < bins; ++b)
    h.expected.push_back(n * RayleighFraction(b * h.bin_width, (b + 1) * h.bin_width, sigma));
  h.expected_beyond = n * RayleighFraction(bins * h.bin_width, INFINITY, sigma);
  return h;
}

int CoverageGrid::EmptyCells() const { return static_cast<int>(std::count(counts.begin(), counts.end(), 0)); }

CoverageGrid CountCorners(const std::vector<CornerResidual>& corners, double width, double height, int cols, int rows) {
  assert(width > 0 && height > 0 && cols > 0 && rows > 0);
  CoverageGrid grid{cols, rows, width, height, std::vector<int>(static_cast<size_t>(cols * rows), 0)};
  for (const CornerResidual& c : corners) {
    const int col = std::clamp(static_cast<int>(std::floor(c.observed.x() * cols / width)), 0, cols - 1);
    const int row = std::clamp(static_cast<int>(std::floor(c.observed.y() * rows / height)), 0, rows - 1);
    ++grid.counts[static_cast<size_t>(row * cols + col)];
  }
  return grid;
}

}  // namespace hexcal

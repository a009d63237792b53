#include "core/sigma_criterion.h"

#include <cmath>
#include <limits>

namespace hexcal {
namespace {

using Vector7d = Eigen::Matrix<double, kParamsPerLeg, 1>;

// √ of a variance that cancellation may have driven a hair below zero.
double SafeSqrt(double variance) { return std::sqrt(std::max(variance, 0.0)); }

}  // namespace

double SigmaSum(const InfoBlock& inverse) {
  double sum = 0;
  for (int j = 0; j < kParamsPerLeg; ++j) sum += SafeSqrt(inverse(j, j));
  return sum;
}

void SigmaSumsAfterAdding(const std::array<InfoBlock, kNumLegs>& inverses,
                          const std::array<Eigen::Matrix<double, kParamsPerLeg, Eigen::Dynamic>, kNumLegs>& candidates,
                          int begin, int n, double* sums) {
  // In chunks that stay in cache rather than 7 x n temporaries.
  constexpr int kChunk = 256;
  Eigen::Matrix<double, kParamsPerLeg, kChunk> u;
  for (int first = 0; first < n; first += kChunk) {
    const int size = std::min(kChunk, n - first);
    double* out = sums + first;
    std::fill(out, out + size, 0.0);
    for (int i = 0; i < kNumLegs; ++i) {
      const auto r = candidates[i].middleCols(begin + first, size);
      u.leftCols(size).noalias() = inverses[i] * r;
      const Vector7d diagonal = inverses[i].diagonal();
      for (int c = 0; c < size; ++c) {
        const double scale = 1 / (1 + r.col(c).dot(u.col(c)));
        double leg_sum = 0;
        for (int j = 0; j < kParamsPerLeg; ++j) leg_sum += SafeSqrt(diagonal[j] - u(j, c) * u(j, c) * scale);
        out[c] += leg_sum;
      }
    }
  }
}

double SigmaSumAfterAddingWithGradient(const std::array<InfoBlock, kNumLegs>& inverses,
                                       const std::array<JacobianRow, kNumLegs>& rows,
                                       std::array<JacobianRow, kNumLegs>* gradient) {
  double total = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const Vector7d r = rows[i].transpose();
    const Vector7d u = inverses[i] * r;
    const double one_plus_q = 1 + r.dot(u);
    Vector7d sigma;
    for (int j = 0; j < kParamsPerLeg; ++j) {
      sigma[j] = std::max(SafeSqrt(inverses[i](j, j) - u[j] * u[j] / one_plus_q), 1e-300);
    }
    total += sigma.sum();
    const Vector7d u_over_sigma = u.cwiseQuotient(sigma);
    const double weighted = u.dot(u_over_sigma);
    (*gradient)[i] =
        (-(inverses[i] * u_over_sigma) / one_plus_q + weighted * u / (one_plus_q * one_plus_q)).transpose();
  }
  return total;
}

}  // namespace hexcal

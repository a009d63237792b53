#include "core/sigma_criterion.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/vector_clones.h"

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
  // In chunks that stay in cache rather than 7 x n temporaries. The square
  // roots run along the chunk, parameter by parameter, so that they vectorise
  // (this file is built with -fno-math-errno: SafeSqrt never sees a negative);
  // each candidate's sum still adds its 7 terms in order, then the legs in order.
  constexpr int kChunk = 256;
  Eigen::Matrix<double, kParamsPerLeg, kChunk> u;
  std::array<double, kChunk> scale, leg_sum;
  for (int first = 0; first < n; first += kChunk) {
    const int size = std::min(kChunk, n - first);
    double* out = sums + first;
    std::fill(out, out + size, 0.0);
    for (int i = 0; i < kNumLegs; ++i) {
      const auto r = candidates[i].middleCols(begin + first, size);
      u.leftCols(size).noalias() = inverses[i] * r;
      for (int c = 0; c < size; ++c) scale[c] = 1 / (1 + r.col(c).dot(u.col(c)));
      std::fill(leg_sum.begin(), leg_sum.begin() + size, 0.0);
      for (int j = 0; j < kParamsPerLeg; ++j) {
        const double diagonal = inverses[i](j, j);
        const double* u_j = u.data() + j;  // u(j, c) = u_j[kParamsPerLeg * c]
        for (int c = 0; c < size; ++c) {
          const double u_jc = u_j[kParamsPerLeg * c];
          leg_sum[c] += SafeSqrt(diagonal - u_jc * u_jc * scale[c]);
        }
      }
      for (int c = 0; c < size; ++c) out[c] += leg_sum[c];
    }
  }
}

SigmaBoundFactors SigmaBoundFactorsOf(const std::array<InfoBlock, kNumLegs>& inverses) {
  SigmaBoundFactors factors;
  for (int i = 0; i < kNumLegs; ++i) {
    Vector7d sigma;
    for (int k = 0; k < kParamsPerLeg; ++k) sigma[k] = SafeSqrt(inverses[i](k, k));
    factors.sigma_sum[i] = sigma.sum();
    const InfoBlock weight = inverses[i] * sigma.cwiseInverse().asDiagonal() * inverses[i];
    factors.upper[i] = Eigen::LLT<InfoBlock>(weight).matrixU();  // W = UᵀU: rᵀWr = |U r|²
  }
  return factors;
}

namespace {

// The loop of both SigmaSumLowerBounds, for double or float columns (read as
// double): inlined into each, so that each is cloned for AVX-512 and AVX2.
template <typename Scalar>
__attribute__((always_inline)) inline void LowerBoundsOf(
    const SigmaBoundFactors& factors,
    const std::array<Eigen::Matrix<Scalar, Eigen::Dynamic, kParamsPerLeg>, kNumLegs>& candidates,
    const std::array<const double*, kNumLegs>& forms, int begin, int n, double* least_sums) {
  std::fill(least_sums, least_sums + n, 0.0);
  for (int i = 0; i < kNumLegs; ++i) {
    const double sigma_sum = factors.sigma_sum[i];
    double u[kParamsPerLeg][kParamsPerLeg];
    for (int j = 0; j < kParamsPerLeg; ++j) {
      for (int k = 0; k < kParamsPerLeg; ++k) u[j][k] = factors.upper[i](j, k);
    }
    // One pass over the candidates: their 7 entries, |U r|² and the bound;
    // with the loops over j and k unrolled, it vectorises along the candidates.
    const Scalar* column[kParamsPerLeg];
    for (int k = 0; k < kParamsPerLeg; ++k) column[k] = candidates[i].col(k).data() + begin;
    const double* __restrict q = forms[i] + begin;
    double* __restrict out = least_sums;
    for (int c = 0; c < n; ++c) {
      double w = 0;
#pragma GCC unroll 7
      for (int j = 0; j < kParamsPerLeg; ++j) {
        double y = 0;
#pragma GCC unroll 7
        for (int k = j; k < kParamsPerLeg; ++k) y += u[j][k] * static_cast<double>(column[k][c]);
        w += y * y;
      }
      // min(a, b) as (a + b - |a - b|) / 2 keeps the loop free of branches (the
      // slack of SigmaUpperBounds covers its rounding); q >= 0 up to drift.
      const double root = std::sqrt(1 + q[c]), a = q[c] * sigma_sum;
      out[c] += sigma_sum - 0.5 * (a + w - std::abs(a - w)) / (root * (root + 1));
    }
  }
}

}  // namespace

HEXCAL_VECTOR_CLONES void SigmaSumLowerBounds(const SigmaBoundFactors& factors,
                                              const std::array<ParameterColumns, kNumLegs>& candidates,
                                              const std::array<const double*, kNumLegs>& forms, int begin, int n,
                                              double* least_sums) {
  LowerBoundsOf(factors, candidates, forms, begin, n, least_sums);
}

HEXCAL_VECTOR_CLONES void SigmaSumLowerBounds(const SigmaBoundFactors& factors,
                                              const std::array<ParameterColumns32, kNumLegs>& candidates,
                                              const std::array<const double*, kNumLegs>& forms, int begin, int n,
                                              double* least_sums) {
  LowerBoundsOf(factors, candidates, forms, begin, n, least_sums);
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

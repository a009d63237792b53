#include "core/quadratic_form_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/sigma_criterion.h"
#include "core/vector_clones.h"

namespace hexcal {
namespace {

using Vector7d = Eigen::Matrix<double, kParamsPerLeg, 1>;
constexpr double kPositiveInfinity = std::numeric_limits<double>::infinity();
// Candidates per ParallelFor item of the cache: their rows (6 x 7 x 8 bytes
// each) stay in cache between the update and the bound.
constexpr int kCacheBlock = 1024;

// One leg's forms after an exchange, for the candidates in [begin, end), by
// Sherman–Morrison: q += (rᵀu_remove)² / d_remove - (rᵀu_add)² / d_add. Both
// projections come from the same 7 loads; unrolled over the parameters, the
// loop vectorises along the candidates. For double or float columns (read as
// double), inlined into each ExchangeForms so that each is cloned.
template <typename Scalar>
__attribute__((always_inline)) inline void ExchangeFormsOf(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, kParamsPerLeg>& columns, const Vector7d& u_add, double d_add,
    const Vector7d& u_remove, double d_remove, int begin, int end, double* __restrict q) {
  // Local copies, so that the compiler sees them unchanged by the stores to q.
  const Scalar* column[kParamsPerLeg];
  double ua[kParamsPerLeg], ur[kParamsPerLeg];
  for (int k = 0; k < kParamsPerLeg; ++k) {
    column[k] = columns.col(k).data();
    ua[k] = u_add[k], ur[k] = u_remove[k];
  }
  for (int c = begin; c < end; ++c) {
    double along_add = 0, along_remove = 0;
#pragma GCC unroll 7
    for (int k = 0; k < kParamsPerLeg; ++k) {
      const double r = static_cast<double>(column[k][c]);
      along_add += ua[k] * r;
      along_remove += ur[k] * r;
    }
    q[c] += along_remove * along_remove / d_remove - along_add * along_add / d_add;
  }
}

HEXCAL_VECTOR_CLONES void ExchangeForms(const ParameterColumns& columns, const Vector7d& u_add, double d_add,
                                        const Vector7d& u_remove, double d_remove, int begin, int end, double* q) {
  ExchangeFormsOf(columns, u_add, d_add, u_remove, d_remove, begin, end, q);
}

HEXCAL_VECTOR_CLONES void ExchangeForms(const ParameterColumns32& columns, const Vector7d& u_add, double d_add,
                                        const Vector7d& u_remove, double d_remove, int begin, int end, double* q) {
  ExchangeFormsOf(columns, u_add, d_add, u_remove, d_remove, begin, end, q);
}

// q = rᵀ A r of the float rows in [begin, end), along the candidates as ExchangeForms.
HEXCAL_VECTOR_CLONES void FormsOf(const ParameterColumns32& columns, const InfoBlock& inverse, int begin, int end,
                                  double* __restrict q) {
  const float* column[kParamsPerLeg];
  double a[kParamsPerLeg][kParamsPerLeg];
  for (int j = 0; j < kParamsPerLeg; ++j) {
    column[j] = columns.col(j).data();
    for (int k = 0; k < kParamsPerLeg; ++k) a[j][k] = inverse(j, k);
  }
  for (int c = begin; c < end; ++c) {
    double r[kParamsPerLeg], form = 0;
#pragma GCC unroll 7
    for (int k = 0; k < kParamsPerLeg; ++k) r[k] = static_cast<double>(column[k][c]);
#pragma GCC unroll 7
    for (int j = 0; j < kParamsPerLeg; ++j) {
      double y = 0;
#pragma GCC unroll 7
      for (int k = 0; k < kParamsPerLeg; ++k) y += a[j][k] * r[k];
      form += r[j] * y;
    }
    q[c] = form;
  }
}

std::array<InfoBlock, kNumLegs> InversesOf(const DesignState& state) {
  std::array<InfoBlock, kNumLegs> inverses;
  for (int i = 0; i < kNumLegs; ++i) inverses[i] = state.inverse(i);
  return inverses;
}

// The S bounds' slack with float rows: rounding them moved a bound by up to
// 1e-6 relative on both presets' rows (M⁻¹ is ill-conditioned).
constexpr double kSingleSlack = 1e-4;

// How far rounding the rows to float moves the S bounds at `state`: the
// largest relative difference, over an even sample of 512 candidates, between
// the bounds of the rows as the cache keeps them (`columns32`, `forms32`) and
// of the double rows.
double FloatBoundDrift(const DesignState& state, const CandidateRows& candidates,
                       const std::array<ParameterColumns32, kNumLegs>& columns32,
                       const std::array<Eigen::ArrayXd, kNumLegs>& forms32) {
  const int n = candidates.size(), count = std::min(n, 512);
  std::array<ParameterColumns, kNumLegs> exact_rows;
  std::array<ParameterColumns32, kNumLegs> rounded_rows;
  std::array<Eigen::ArrayXd, kNumLegs> exact_forms, rounded_forms;
  std::array<const double*, kNumLegs> exact_pointers, rounded_pointers;
  for (int i = 0; i < kNumLegs; ++i) {
    exact_rows[i].resize(count, kParamsPerLeg);
    rounded_rows[i].resize(count, kParamsPerLeg);
    exact_forms[i].resize(count);
    rounded_forms[i].resize(count);
    for (int k = 0; k < count; ++k) {
      const int j = static_cast<int>(static_cast<int64_t>(k) * n / count);
      const auto r = candidates.legs[i].col(j);
      exact_rows[i].row(k) = r.transpose();
      rounded_rows[i].row(k) = columns32[i].row(j);
      exact_forms[i][k] = r.dot(state.inverse(i) * r);
      rounded_forms[i][k] = forms32[i][j];
    }
    exact_pointers[i] = exact_forms[i].data();
    rounded_pointers[i] = rounded_forms[i].data();
  }
  const SigmaBoundFactors factors = SigmaBoundFactorsOf(InversesOf(state));
  std::vector<double> exact(count), rounded(count);
  SigmaSumLowerBounds(factors, exact_rows, exact_pointers, 0, count, exact.data());
  SigmaSumLowerBounds(factors, rounded_rows, rounded_pointers, 0, count, rounded.data());
  double drift = 0;
  for (int k = 0; k < count; ++k) drift = std::max(drift, std::abs(rounded[k] / exact[k] - 1));
  return std::isfinite(drift) ? drift : kPositiveInfinity;
}

}  // namespace

void QuadraticFormCache::Reset(const DesignState& state, const CandidateRows& candidates, int threads,
                               bool single_precision) {
  const int n = candidates.size();
  const bool copy = source_ != &candidates || single_ != single_precision ||
                    (single_precision ? columns32_[0].rows() : columns_[0].rows()) != n;
  single_ = single_precision;
  for (int i = 0; i < kNumLegs; ++i) {
    if (copy) {
      columns_[i].resize(single_ ? 0 : n, kParamsPerLeg);
      columns32_[i].resize(single_ ? n : 0, kParamsPerLeg);
    }
    q_[i].resize(n);
  }
  source_ = &candidates;
  // q_j = r_jᵀ M⁻¹ r_j, block by block on every core: each candidate's form
  // comes out the same as from the whole product at once. In single
  // precision, of the rows as rounded to float: the rows the updates read.
  ParallelForBlocks(n, kCacheBlock, threads, [&](int begin, int end) {
    for (int i = 0; i < kNumLegs; ++i) {
      const auto r = candidates.legs[i].middleCols(begin, end - begin);
      if (single_) {
        if (copy) columns32_[i].middleRows(begin, end - begin) = r.transpose().cast<float>();
        FormsOf(columns32_[i], state.inverse(i), begin, end, q_[i].data());
        continue;
      }
      if (copy) columns_[i].middleRows(begin, end - begin) = r.transpose();
      q_[i].segment(begin, end - begin) = r.cwiseProduct(state.inverse(i) * r).colwise().sum().transpose().array();
    }
  });
  updates_ = 0;
  // Where rounding matters more than a tenth of the slack (an ill-conditioned
  // plan), the rows stay double: the bounds must stay bounds.
  if (single_ && FloatBoundDrift(state, candidates, columns32_, q_) > 0.1 * kSingleSlack) {
    Reset(state, candidates, threads, /*single_precision=*/false);
  }
}

void QuadraticFormCache::Update(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows,
                                double sign) {
  for (int i = 0; i < kNumLegs; ++i) {
    const Vector7d u = state.inverse(i) * rows[i].transpose();
    const double denominator = 1 + sign * rows[i].dot(u.transpose());
    // In single precision, of the float rows, as the forms themselves.
    const Eigen::ArrayXd projection = single_ ? (columns32_[i].cast<double>() * u).array().eval()
                                              : (u.transpose() * candidates.legs[i]).transpose().array().eval();
    q_[i] -= sign * projection.square() / denominator;
  }
  ++updates_;
}

void QuadraticFormCache::Exchanged(const DesignState& before, const PoseRows& added, const DesignState& with_added,
                                   const PoseRows& removed, const CandidateRows& candidates, int threads,
                                   const DesignState* after, std::vector<double>* sigma_bounds) {
  // Per leg, by Sherman–Morrison: q += (rᵀu_remove)² / d_remove - (rᵀu_add)² / d_add.
  std::array<Vector7d, kNumLegs> u_add, u_remove;
  std::array<double, kNumLegs> d_add, d_remove;
  for (int i = 0; i < kNumLegs; ++i) {
    u_add[i] = before.inverse(i) * added[i].transpose();
    u_remove[i] = with_added.inverse(i) * removed[i].transpose();
    d_add[i] = 1 + added[i].dot(u_add[i].transpose());
    d_remove[i] = 1 - removed[i].dot(u_remove[i].transpose());
  }
  const bool bound = after && sigma_bounds;
  SigmaBoundFactors factors;
  if (bound) {
    factors = SigmaBoundFactorsOf(InversesOf(*after));
    sigma_bounds->resize(candidates.size());
  }
  // Blocks of candidates on every core: all legs' forms, then (in cache) the bounds.
  ParallelForBlocks(candidates.size(), kCacheBlock, threads, [&](int begin, int end) {
    for (int i = 0; i < kNumLegs; ++i) {
      if (single_) {
        ExchangeForms(columns32_[i], u_add[i], d_add[i], u_remove[i], d_remove[i], begin, end, q_[i].data());
      } else {
        ExchangeForms(columns_[i], u_add[i], d_add[i], u_remove[i], d_remove[i], begin, end, q_[i].data());
      }
    }
    if (bound) SigmaUpperBoundsOf(factors, begin, end, sigma_bounds->data() + begin);
  });
  updates_ += 2;
}

void QuadraticFormCache::Added(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows) {
  Update(state, candidates, rows, +1);
}

void QuadraticFormCache::Removed(const DesignState& state, const CandidateRows& candidates, const PoseRows& rows) {
  Update(state, candidates, rows, -1);
}

void QuadraticFormCache::SigmaUpperBoundsOf(const SigmaBoundFactors& factors, int begin, int end,
                                            double* bounds) const {
  std::array<const double*, kNumLegs> forms;
  for (int i = 0; i < kNumLegs; ++i) forms[i] = q_[i].data();
  if (single_) {
    SigmaSumLowerBounds(factors, columns32_, forms, begin, end - begin, bounds);
  } else {
    SigmaSumLowerBounds(factors, columns_, forms, begin, end - begin, bounds);
  }
  // The exact values (SigmaSumsAfterAdding) round differently and q drifts
  // between resets: a relative slack keeps the bound above them. Rows rounded
  // to float (relative error 6e-8) move a bound by up to 1e-6 relative on the
  // presets' plans, M⁻¹ being ill-conditioned (design_criteria_test measures
  // it and checks the bounds against exact S; each Reset samples it and keeps
  // the rows double beyond a tenth of the slack): kSingleSlack is a hundred
  // times that, and costs only a few more exact evaluations.
  const double slack = single_ ? kSingleSlack : 1e-9;
  for (int j = 0; j < end - begin; ++j) {
    bounds[j] = bounds[j] > 0 ? kNumParams / bounds[j] * (1 + slack) : kPositiveInfinity;
  }
}

void QuadraticFormCache::SigmaUpperBounds(const DesignState& state, std::vector<double>* bounds, int threads) const {
  const SigmaBoundFactors factors = SigmaBoundFactorsOf(InversesOf(state));
  bounds->resize(q_[0].size());
  ParallelForBlocks(static_cast<int>(q_[0].size()), kCacheBlock, threads, [&](int begin, int end) {
    SigmaUpperBoundsOf(factors, begin, end, bounds->data() + begin);
  });
}

void QuadraticFormCache::Growth(std::vector<double>* growth) const {
  Eigen::ArrayXd product = 1 + q_[0];
  for (int i = 1; i < kNumLegs; ++i) product *= 1 + q_[i];
  growth->assign(product.data(), product.data() + product.size());
}

}  // namespace hexcal
#include "core/sigma_design.h"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "core/parallel.h"
#include "core/working_set_design.h"

namespace hexcal {
namespace {

using Blocks = std::array<InfoBlock, kNumLegs>;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Φ of the design and, per leg, S_i^-½ M_i⁻¹ (so that d = Σ_i |S_i^-½ M_i⁻¹ r_i|²).
// False when a block is singular.
bool SigmaFactors(const Blocks& blocks, Blocks* factors, double* sigma_sum) {
  *sigma_sum = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::LLT<InfoBlock> llt(blocks[i]);
    if (llt.info() != Eigen::Success) return false;
    const InfoBlock inverse = llt.solve(InfoBlock::Identity());
    if (!(inverse.diagonal().array() > 0).all()) return false;
    const Eigen::Matrix<double, kParamsPerLeg, 1> sigma = inverse.diagonal().cwiseSqrt();
    *sigma_sum += sigma.sum();
    (*factors)[i] = sigma.cwiseSqrt().cwiseInverse().asDiagonal() * inverse;
  }
  return true;
}

double SigmaSumOf(const Blocks& blocks) {
  Blocks unused;
  double sum;
  return SigmaFactors(blocks, &unused, &sum) ? sum : kInfinity;
}

void DirectionalFunction(const Blocks& factors, const CandidateRows& candidates, Eigen::ArrayXd* d, int threads) {
  d->resize(candidates.size());
  ParallelForBlocks(candidates.size(), 1024, threads, [&](int begin, int end) {
    Eigen::Map<Eigen::ArrayXd> out(d->data() + begin, end - begin);
    out.setZero();
    for (int i = 0; i < kNumLegs; ++i) {
      const Eigen::MatrixXd y = factors[i] * candidates.legs[i].middleCols(begin, end - begin);
      out += y.colwise().squaredNorm().transpose().array();
    }
  });
}

// The weight δ in [0, max_step] moved from candidate l to candidate k that
// minimises Φ, by golden-section search (Φ is convex along the segment); 0 if
// no step lowers Φ.
double SigmaExchangeStep(const Blocks& blocks, const CandidateRows& candidates, int k, int l, double max_step) {
  const SigmaSumAlongExchange phi(blocks, candidates, k, l);
  const double ratio = 0.5 * (std::sqrt(5.0) - 1);
  double lo = 0, hi = max_step;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo), f1 = phi(x1), f2 = phi(x2);
  for (int iteration = 0; iteration < 40; ++iteration) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - ratio * (hi - lo), f1 = phi(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + ratio * (hi - lo), f2 = phi(x2);
    }
  }
  const double best = 0.5 * (lo + hi);
  return phi(best) < phi(0) ? best : 0;
}

// Up to eight vertex exchanges: weight from the support point with the smallest
// d to the candidate with the largest, while a step lowers Φ. `blocks` are
// M_i(w), kept up to date.
void VertexExchanges(const CandidateRows& candidates, Eigen::ArrayXd d, int best, Eigen::ArrayXd* w,
                     Blocks* blocks) {
  for (int exchange = 0; exchange < 8; ++exchange) {
    int worst = -1;
    double worst_d = kInfinity;
    for (int j = 0; j < candidates.size(); ++j) {
      if ((*w)[j] > 0 && d[j] < worst_d) worst_d = d[j], worst = j;
    }
    if (worst < 0 || worst == best) return;
    const double delta = SigmaExchangeStep(*blocks, candidates, best, worst, (*w)[worst]);
    if (delta <= 0) return;
    (*w)[best] += delta;
    (*w)[worst] -= delta;
    for (int i = 0; i < kNumLegs; ++i) {
      const auto rk = candidates.legs[i].col(best), rl = candidates.legs[i].col(worst);
      (*blocks)[i] += delta * (rk * rk.transpose() - rl * rl.transpose());
    }
    d[worst] = kInfinity;  // look for the next-worst support point
  }
}

}  // namespace

SigmaSumAlongExchange::SigmaSumAlongExchange(const Blocks& blocks, const CandidateRows& candidates, int to,
                                             int from) {
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::LLT<InfoBlock> llt(blocks[i]);
    if (llt.info() != Eigen::Success) {
      positive_definite_ = false;
      return;
    }
    const InfoBlock inverse = llt.solve(InfoBlock::Identity());
    const auto r_to = candidates.legs[i].col(to), r_from = candidates.legs[i].col(from);
    Leg& leg = legs_[i];
    leg.variance = inverse.diagonal();
    leg.p = inverse * r_to;
    leg.q = inverse * r_from;
    leg.a = r_to.dot(leg.p);
    leg.b = r_from.dot(leg.q);
    leg.c = r_to.dot(leg.q);
  }
}

double SigmaSumAlongExchange::operator()(double delta) const {
  if (!positive_definite_) return kInfinity;
  double sum = 0;
  for (const Leg& leg : legs_) {
    const double g = (1 + delta * leg.a) * (1 - delta * leg.b) + delta * delta * leg.c * leg.c;
    if (!(g > 0)) return kInfinity;
    const double pp = delta * (1 - delta * leg.b) / g, pq = 2 * delta * delta * leg.c / g,
                 qq = -delta * (1 + delta * leg.a) / g;
    for (int k = 0; k < kParamsPerLeg; ++k) {
      const double variance = leg.variance[k] - (pp * leg.p[k] * leg.p[k] + pq * leg.p[k] * leg.q[k] +
                                                 qq * leg.q[k] * leg.q[k]);
      if (!(variance > 0)) return kInfinity;
      sum += std::sqrt(variance);
    }
  }
  return sum;
}

double SigmaDesign::SigmaSumBound() const { return max_d > 0 ? sigma_sum * std::sqrt(sigma_sum / max_d) : 0; }

namespace {

// w_j <- w_j (d_j / Φ)^ρ, normalised. Yu (2010) proves ρ = ½ monotone for
// this A-type criterion; ρ = 1 can take half the iterations (533 against
// 1 064 on the working set of INRIA's default 10⁵-candidate plan) but is not
// guaranteed to, so its step is kept only when it lowers Φ. Sets `blocks` to
// the new M_i(w).
void MultiplicativeStep(const CandidateRows& candidates, const Eigen::ArrayXd& d, double sigma_sum,
                        Eigen::ArrayXd* w, Blocks* blocks) {
  Eigen::ArrayXd bold = *w * (d / sigma_sum);
  bold /= bold.sum();
  *blocks = DesignInformation(candidates, bold);
  if (SigmaSumOf(*blocks) < sigma_sum) {
    *w = std::move(bold);
    return;
  }
  *w *= (d / sigma_sum).sqrt();
  *w /= w->sum();
  *blocks = DesignInformation(candidates, *w);
}

// The multiplicative algorithm with vertex exchanges on `candidates` themselves.
StatusOr<SigmaDesign> SolveSigmaOptimal(const CandidateRows& candidates, const OptimalDesignOptions& options,
                                        const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const int count = candidates.size();
  if (count < kParamsPerLeg) return Status::BadInput("the optimal design needs at least 7 candidates");
  Eigen::ArrayXd w = Eigen::ArrayXd::Constant(count, 1.0 / count), d;
  SigmaDesign design;
  Blocks blocks = DesignInformation(candidates, w), factors;
  for (design.iterations = 0; design.iterations < options.max_iterations; ++design.iterations) {
    if (hooks.Cancelled()) return Status::Cancelled("optimal design cancelled");
    if (!SigmaFactors(blocks, &factors, &design.sigma_sum)) {
      return Status::BadInput("the candidate set does not identify all 42 parameters (singular information)");
    }
    DirectionalFunction(factors, candidates, &d, options.threads);
    Eigen::Index best;
    design.max_d = d.maxCoeff(&best);
    design.gap = design.max_d / design.sigma_sum - 1;
    if (design.gap < options.gap_tolerance) {
      design.converged = true;
      break;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > options.max_seconds) break;
    MultiplicativeStep(candidates, d, design.sigma_sum, &w, &blocks);
    VertexExchanges(candidates, d, static_cast<int>(best), &w, &blocks);
  }
  design.weights.assign(w.data(), w.data() + count);
  design.support = static_cast<int>((w > 1e-8).count());
  return design;
}

// The design on `working` over every candidate (working_set_design.h): d is
// the directional function, violating above Φ.
double PriceSigma(const CandidateRows& all, const CandidateRows& working, SigmaDesign* design, Eigen::ArrayXd* d,
                  int threads) {
  const Eigen::Map<const Eigen::ArrayXd> w(design->weights.data(), design->weights.size());
  Blocks factors;
  if (!SigmaFactors(DesignInformation(working, w), &factors, &design->sigma_sum)) {
    design->gap = kInfinity;
    return kInfinity;
  }
  DirectionalFunction(factors, all, d, threads);
  design->max_d = d->maxCoeff();
  design->gap = design->max_d / design->sigma_sum - 1;
  return design->sigma_sum;
}

}  // namespace

StatusOr<SigmaDesign> ComputeSigmaOptimalDesign(const CandidateRows& candidates, const OptimalDesignOptions& options,
                                                const JobHooks& hooks) {
  return SolveOnWorkingSet<SigmaDesign>(
      candidates, options, hooks, SolveSigmaOptimal,
      [&](const CandidateRows& all, const CandidateRows& working, SigmaDesign* design, Eigen::ArrayXd* d) {
        return PriceSigma(all, working, design, d, options.threads);
      });
}

double SEfficiencyLowerBound(const std::array<InfoBlock, kNumLegs>& plan_blocks, int num_poses,
                             const SigmaDesign& design) {
  const double plan_sum = SigmaSumOf(plan_blocks);
  if (!std::isfinite(plan_sum) || num_poses <= 0) return 0;
  return design.SigmaSumBound() / (std::sqrt(static_cast<double>(num_poses)) * plan_sum);
}

}  // namespace hexcal

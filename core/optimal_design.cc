#include "core/optimal_design.h"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>

#include "core/parallel.h"
#include "core/working_set_design.h"

namespace hexcal {
namespace {

constexpr double kP = kNumParams;

bool Invert(const std::array<InfoBlock, kNumLegs>& blocks, std::array<InfoBlock, kNumLegs>* inverses,
            std::array<InfoBlock, kNumLegs>* cholesky_inverses, double* log_det) {
  *log_det = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::LLT<InfoBlock> llt(blocks[i]);
    if (llt.info() != Eigen::Success) return false;
    const InfoBlock lower = llt.matrixL();
    if ((lower.diagonal().array() <= 0).any()) return false;
    (*cholesky_inverses)[i] = lower.triangularView<Eigen::Lower>().solve(InfoBlock::Identity());
    (*inverses)[i] = (*cholesky_inverses)[i].transpose() * (*cholesky_inverses)[i];
    *log_det += 2 * lower.diagonal().array().log().sum();
  }
  return true;
}

void VarianceFromCholesky(const std::array<InfoBlock, kNumLegs>& cholesky_inverses, const CandidateRows& candidates,
                          int begin, int end, double* out) {
  const int n = end - begin;
  Eigen::Map<Eigen::ArrayXd> variance(out, n);
  variance.setZero();
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::MatrixXd y =
        cholesky_inverses[i].triangularView<Eigen::Lower>() * candidates.legs[i].middleCols(begin, n);
    variance += y.colwise().squaredNorm().transpose().array();
  }
}

void ParallelVariance(const std::array<InfoBlock, kNumLegs>& cholesky_inverses, const CandidateRows& candidates,
                      Eigen::ArrayXd* variance, int threads) {
  variance->resize(candidates.size());
  ParallelForBlocks(candidates.size(), 1024, threads, [&](int begin, int end) {
    VarianceFromCholesky(cholesky_inverses, candidates, begin, end, variance->data() + begin);
  });
}

// Optimal weight δ in [0, w_l] moved from candidate l to k: maximises
// Σ_i log[(1 + δ a_i)(1 - δ b_i) + δ² c_i²] (determinant lemma for a rank-two update).
double ExchangeStep(const std::array<InfoBlock, kNumLegs>& inverses, const CandidateRows& candidates, int k, int l,
                    double max_step) {
  std::array<double, kNumLegs> a, b, c;
  for (int i = 0; i < kNumLegs; ++i) {
    const auto rk = candidates.legs[i].col(k), rl = candidates.legs[i].col(l);
    a[i] = rk.dot(inverses[i] * rk);
    b[i] = rl.dot(inverses[i] * rl);
    c[i] = rk.dot(inverses[i] * rl);
  }
  auto slope = [&](double delta) {
    double s = 0;
    for (int i = 0; i < kNumLegs; ++i) {
      const double g = (1 + delta * a[i]) * (1 - delta * b[i]) + delta * delta * c[i] * c[i];
      const double dg = a[i] * (1 - delta * b[i]) - b[i] * (1 + delta * a[i]) + 2 * delta * c[i] * c[i];
      s += dg / g;
    }
    return s;
  };
  if (slope(0) <= 0) return 0;
  if (slope(max_step) >= 0) return max_step;
  double lo = 0, hi = max_step;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (slope(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

std::array<InfoBlock, kNumLegs> DesignInformation(const CandidateRows& candidates, const Eigen::ArrayXd& w) {
  std::array<InfoBlock, kNumLegs> blocks;
  for (int i = 0; i < kNumLegs; ++i) {
    const auto& r = candidates.legs[i];
    blocks[i] = r * w.matrix().asDiagonal() * r.transpose();
  }
  return blocks;
}

double OptimalDesign::LogDetBound() const { return log_det + kP * std::log(max_variance / kP); }

void VarianceFunction(const std::array<InfoBlock, kNumLegs>& inverses, const CandidateRows& candidates,
                      Eigen::ArrayXd* variance) {
  const int count = candidates.size();
  variance->setZero(count);
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::MatrixXd x = inverses[i] * candidates.legs[i];
    *variance += candidates.legs[i].cwiseProduct(x).colwise().sum().transpose().array();
  }
}

namespace {

// The multiplicative algorithm with vertex exchanges on `candidates` themselves.
StatusOr<OptimalDesign> SolveDOptimal(const CandidateRows& candidates, const OptimalDesignOptions& options,
                                      const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const int count = candidates.size();
  if (count < kParamsPerLeg) return Status::BadInput("the optimal design needs at least 7 candidates");

  Eigen::ArrayXd w = Eigen::ArrayXd::Constant(count, 1.0 / count);
  std::array<InfoBlock, kNumLegs> blocks = DesignInformation(candidates, w), inverses, cholesky_inverses;
  OptimalDesign design;
  Eigen::ArrayXd d;
  for (design.iterations = 0; design.iterations < options.max_iterations; ++design.iterations) {
    if (hooks.Cancelled()) return Status::Cancelled("optimal design cancelled");
    if (!Invert(blocks, &inverses, &cholesky_inverses, &design.log_det)) {
      return Status::BadInput("the candidate set does not identify all 42 parameters (singular information)");
    }
    ParallelVariance(cholesky_inverses, candidates, &d, options.threads);
    Eigen::Index best;
    design.max_variance = d.maxCoeff(&best);
    design.gap = design.max_variance / kP - 1;
    if (design.gap < options.gap_tolerance) {
      design.converged = true;
      break;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > options.max_seconds) break;
    // Multiplicative step: Σ w d = p, so the weights stay normalised.
    w *= d / kP;
    // Vertex exchanges: from the worst support point to the best candidate, while it pays.
    blocks = DesignInformation(candidates, w);
    for (int exchange = 0; exchange < 8; ++exchange) {
      if (!Invert(blocks, &inverses, &cholesky_inverses, &design.log_det)) break;
      Eigen::Index worst = -1;
      double worst_d = std::numeric_limits<double>::infinity();
      for (int j = 0; j < count; ++j) {
        if (w[j] > 0 && d[j] < worst_d) {
          worst_d = d[j];
          worst = j;
        }
      }
      if (worst < 0 || worst == best) break;
      const double delta = ExchangeStep(inverses, candidates, static_cast<int>(best), static_cast<int>(worst), w[worst]);
      if (delta <= 0) break;
      w[best] += delta;
      w[worst] -= delta;
      for (int i = 0; i < kNumLegs; ++i) {
        const auto rk = candidates.legs[i].col(best), rl = candidates.legs[i].col(worst);
        blocks[i] += delta * (rk * rk.transpose() - rl * rl.transpose());
      }
      d[worst] = std::numeric_limits<double>::infinity();  // look for the next-worst support point
    }
  }
  design.weights.assign(w.data(), w.data() + count);
  design.support = static_cast<int>((w > 1e-8).count());
  return design;
}

// The design on `working` over every candidate (working_set_design.h): d is the
// variance function, violating above p.
double PriceD(const CandidateRows& all, const CandidateRows& working, OptimalDesign* design, Eigen::ArrayXd* d,
              int threads) {
  const Eigen::Map<const Eigen::ArrayXd> w(design->weights.data(), design->weights.size());
  std::array<InfoBlock, kNumLegs> inverses, cholesky_inverses;
  if (!Invert(DesignInformation(working, w), &inverses, &cholesky_inverses, &design->log_det)) {
    design->gap = std::numeric_limits<double>::infinity();
    return std::numeric_limits<double>::infinity();
  }
  ParallelVariance(cholesky_inverses, all, d, threads);
  design->max_variance = d->maxCoeff();
  design->gap = design->max_variance / kP - 1;
  return kP;
}

}  // namespace

StatusOr<OptimalDesign> ComputeOptimalDesign(const CandidateRows& candidates, const OptimalDesignOptions& options,
                                             const JobHooks& hooks) {
  return SolveOnWorkingSet<OptimalDesign>(
      candidates, options, hooks, SolveDOptimal,
      [&](const CandidateRows& all, const CandidateRows& working, OptimalDesign* design, Eigen::ArrayXd* d) {
        return PriceD(all, working, design, d, options.threads);
      });
}

double DEfficiencyLowerBound(const std::array<InfoBlock, kNumLegs>& plan_blocks, int num_poses,
                             const OptimalDesign& design) {
  double log_det = 0;
  for (const InfoBlock& block : plan_blocks) {
    const Eigen::LLT<InfoBlock> llt(block / num_poses);
    if (llt.info() != Eigen::Success) return 0;
    log_det += 2 * InfoBlock(llt.matrixL()).diagonal().array().log().sum();
  }
  return std::exp((log_det - design.LogDetBound()) / kP);
}

}  // namespace hexcal

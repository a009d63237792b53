#include "core/design_criteria.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/sigma_criterion.h"

namespace hexcal {
namespace {

using Vector7d = Eigen::Matrix<double, kParamsPerLeg, 1>;
constexpr double kNegativeInfinity = -std::numeric_limits<double>::infinity();

// Root of f(μ) = 1 + Σ z_k² / (λ_k - μ) in (lo, hi), where f(lo+) < 0 < f(hi-)
// (f increases between consecutive poles), by Newton from `start`, kept inside
// the shrinking bracket by bisection.
double SecularRoot(const Vector7d& lambda, const Vector7d& z2, double lo, double hi, double start) {
  double mu = start > lo && start < hi ? start : 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100; ++iteration) {
    double f = 1, df = 0;
    for (int k = 0; k < kParamsPerLeg; ++k) {
      const double d = lambda[k] - mu;
      f += z2[k] / d;
      df += z2[k] / (d * d);
    }
    if (f < 0) lo = mu;
    else hi = mu;
    double next = mu - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - mu) <= 1e-15 * std::max(std::abs(mu), 1e-300) || hi - lo <= 1e-15 * std::abs(hi)) {
      return next;
    }
    mu = next;
  }
  return mu;
}

// Smallest root of the secular equation written in t = μ - λ_1 (z_1 ≠ 0):
//   h(t) = t (1 + Σ_{k>1} z_k² / (d_k - t)) - z_1² = 0,  d_k = λ_k - λ_1, t in (0, t_max).
// h is increasing and convex there, so Newton from t = 0 lands right of the root
// and then descends monotonically: a handful of steps, no bisection.
double SmallestSecularRoot(const Vector7d& lambda, const Vector7d& z2, double t_max) {
  double t = 0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    double s = 0, ds = 0;
    for (int k = 1; k < kParamsPerLeg; ++k) {
      const double d = lambda[k] - lambda[0] - t;
      s += z2[k] / d;
      ds += z2[k] / (d * d);
    }
    const double h = t * (1 + s) - z2[0], dh = 1 + s + t * ds;
    double next = t - h / dh;
    if (!(next < t_max)) next = 0.5 * (t + t_max);  // never step onto the pole
    if (next <= 0) next = 0.5 * t;
    if (std::abs(next - t) <= 1e-15 * next) return lambda[0] + next;
    t = next;
  }
  return lambda[0] + t;
}

double LogDetOrMinusInfinity(const InfoBlock& block) {
  const Eigen::LLT<InfoBlock> llt(block);
  if (llt.info() != Eigen::Success) return kNegativeInfinity;
  // A concrete vector: an `auto` Eigen expression here would dangle.
  const Vector7d diagonal = InfoBlock(llt.matrixL()).diagonal();
  if ((diagonal.array() <= 0).any()) return kNegativeInfinity;
  return 2 * diagonal.array().log().sum();
}

// L⁻¹ and M⁻¹ = L⁻ᵀ L⁻¹ from a block's Cholesky factor M = L Lᵀ: the one
// sequence of operations of Refactor and SigmaSumIfClearlyFullRank, whose
// values must agree bit for bit.
void InvertByCholesky(const InfoBlock& lower, InfoBlock* cholesky_inverse, InfoBlock* inverse) {
  *cholesky_inverse = lower.triangularView<Eigen::Lower>().solve(InfoBlock::Identity());
  *inverse = cholesky_inverse->transpose() * *cholesky_inverse;
}

// Σσ of the blocks as DesignState's Refactor computes it (the same operations
// in the same order), when a sufficient test proves them full rank without an
// eigendecomposition: λ_min >= 1 / tr M⁻¹ and λ_max <= tr M, so
// tr M · tr M⁻¹ below 1 / (7ε), with a margin of 10³ for the eigensolver's
// rounding, passes Refactor's test λ_min > 7ε λ_max. nullopt when the test
// cannot tell (Refactor decides); 0 when a block is not positive definite.
std::optional<double> SigmaSumIfClearlyFullRank(const std::array<InfoBlock, kNumLegs>& blocks) {
  constexpr double kMaxConditioning = 1e-3 / (kParamsPerLeg * std::numeric_limits<double>::epsilon());
  double sigma_sum = 0;
  for (const InfoBlock& block : blocks) {
    const Eigen::LLT<InfoBlock> llt(block);
    if (llt.info() != Eigen::Success) return 0.0;
    InfoBlock cholesky_inverse, inverse;
    InvertByCholesky(llt.matrixL(), &cholesky_inverse, &inverse);
    if (!(block.trace() * inverse.trace() < kMaxConditioning)) return std::nullopt;
    sigma_sum += SigmaSum(inverse);
  }
  return sigma_sum;
}

}  // namespace

const std::vector<std::pair<std::string, Criterion>>& CriterionNames() {
  static const std::vector<std::pair<std::string, Criterion>> kNames = {
      {"O1", Criterion::kO1}, {"O2", Criterion::kO2}, {"O3", Criterion::kO3}, {"O4", Criterion::kO4},
      {"D", Criterion::kD},   {"A", Criterion::kA},   {"E", Criterion::kE},   {"S", Criterion::kS}};
  return kNames;
}

std::optional<Criterion> ParseCriterion(const std::string& text) {
  for (const auto& [name, criterion] : CriterionNames())
    if (text == name) return criterion;
  return std::nullopt;
}

const char* CriterionName(Criterion criterion) {
  for (const auto& [name, value] : CriterionNames())
    if (value == criterion) return name.c_str();
  return "?";
}

PoseRows CandidateRows::Rows(int j) const {
  PoseRows rows;
  for (int i = 0; i < kNumLegs; ++i) rows[i] = legs[i].col(j).transpose();
  return rows;
}

void CandidateRows::Resize(int count) {
  for (auto& leg : legs) leg.resize(kParamsPerLeg, count);
}

void CandidateRows::Set(int j, const PoseRows& rows) {
  for (int i = 0; i < kNumLegs; ++i) legs[i].col(j) = rows[i].transpose();
}

void RankOneExtremeEigenvalues(const Vector7d& lambda, const Vector7d& z, double* smallest, double* largest) {
  const Vector7d z2 = z.cwiseAbs2();
  const double norm2 = z2.sum();
  const double scale = std::max(std::abs(lambda[kParamsPerLeg - 1]), norm2);
  const double negligible = 1e-30 * scale * scale;
  // Largest: in (λ_7, λ_7 + |z|²].
  // Starts from second-order perturbation theory, μ ≈ λ_k + z_k² + Σ_{m≠k} z_k² z_m² / (λ_k - λ_m),
  // which is already close in the usual case of a well-separated extreme eigenvalue.
  auto perturbed = [&](int k) {
    double mu = lambda[k] + z2[k];
    for (int m = 0; m < kParamsPerLeg; ++m) {
      if (m != k && lambda[k] != lambda[m]) mu += z2[k] * z2[m] / (lambda[k] - lambda[m]);
    }
    return mu;
  };
  const int top = kParamsPerLeg - 1;
  *largest = norm2 <= negligible ? lambda[top] : SecularRoot(lambda, z2, lambda[top], lambda[top] + norm2, perturbed(top));
  // Smallest: λ_1 itself if z has no component on its eigenvector (deflation),
  // else the root in (λ_1, min(λ_2, λ_1 + |z|²)).
  const double upper = std::min(lambda[1], lambda[0] + norm2);
  if (z2[0] <= negligible || upper - lambda[0] <= 1e-15 * scale) {
    *smallest = lambda[0];
  } else {
    *smallest = SmallestSecularRoot(lambda, z2, upper - lambda[0]);
  }
}

DesignState::DesignState(const std::array<InfoBlock, kNumLegs>& blocks, int num_poses)
    : blocks_(blocks), num_poses_(num_poses) {
  Refactor();
}

DesignState DesignState::FromRows(const std::vector<PoseRows>& poses) {
  std::array<InfoBlock, kNumLegs> blocks;
  for (InfoBlock& b : blocks) b.setZero();
  for (const PoseRows& rows : poses) {
    for (int i = 0; i < kNumLegs; ++i) blocks[i].noalias() += rows[i].transpose() * rows[i];
  }
  return DesignState(blocks, static_cast<int>(poses.size()));
}

void DesignState::Refactor() {
  full_rank_ = true;
  log_det_ = 0;
  trace_inverse_ = 0;
  sigma_sum_ = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::SelfAdjointEigenSolver<InfoBlock> eigen(blocks_[i]);
    eigenvalues_[i] = eigen.eigenvalues();
    eigenvectors_[i] = eigen.eigenvectors();
    const Eigen::LLT<InfoBlock> llt(blocks_[i]);
    const double tolerance = kParamsPerLeg * std::numeric_limits<double>::epsilon() * eigenvalues_[i].maxCoeff();
    if (llt.info() != Eigen::Success || eigenvalues_[i][0] <= tolerance) {
      full_rank_ = false;
      continue;
    }
    const InfoBlock lower = llt.matrixL();
    InvertByCholesky(lower, &cholesky_inverse_[i], &inverse_[i]);
    log_det_ += 2 * lower.diagonal().array().log().sum();
    trace_inverse_ += inverse_[i].trace();
    sigma_sum_ += SigmaSum(inverse_[i]);
  }
}

double DesignState::FromSpectrum(Criterion criterion, double log_det, double trace_inverse, double lambda_min,
                                 double lambda_max, int num_poses) const {
  lambda_min = std::max(lambda_min, 0.0);
  switch (criterion) {
    case Criterion::kO1:  // (Π σ)^(1/42) / √m with Π σ = det(M)^(1/2)
      return std::isfinite(log_det) ? std::exp(log_det / (2.0 * kNumParams)) / std::sqrt(num_poses) : 0.0;
    case Criterion::kD: return std::isfinite(log_det) ? std::exp(log_det / kNumParams) : 0.0;
    case Criterion::kA: return trace_inverse > 0 && std::isfinite(trace_inverse) ? kNumParams / trace_inverse : 0.0;
    case Criterion::kO2: return lambda_max > 0 ? std::sqrt(lambda_min / lambda_max) : 0.0;
    case Criterion::kO3: return std::sqrt(lambda_min);
    case Criterion::kO4: return lambda_max > 0 ? lambda_min / std::sqrt(lambda_max) : 0.0;
    case Criterion::kE: return lambda_min;
    case Criterion::kS: return 0.0;  // not spectral: Value and the S branches compute it
  }
  return 0.0;
}

double DesignState::Value(Criterion criterion) const {
  if (criterion == Criterion::kS) return full_rank_ && sigma_sum_ > 0 ? kNumParams / sigma_sum_ : 0.0;
  double lambda_min = std::numeric_limits<double>::infinity(), lambda_max = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    lambda_min = std::min(lambda_min, eigenvalues_[i][0]);
    lambda_max = std::max(lambda_max, eigenvalues_[i][kParamsPerLeg - 1]);
  }
  return FromSpectrum(criterion, full_rank_ ? log_det_ : kNegativeInfinity,
                      full_rank_ ? trace_inverse_ : std::numeric_limits<double>::infinity(), lambda_min, lambda_max,
                      num_poses_);
}

void DesignState::ScoreAdditions(Criterion criterion, const CandidateRows& candidates, int begin, int end,
                                 double* scores) const {
  const int n = end - begin;
  if (n <= 0) return;
  const bool uses_inverse = criterion == Criterion::kO1 || criterion == Criterion::kD ||
                            criterion == Criterion::kA || criterion == Criterion::kS;
  if (uses_inverse && !full_rank_) {  // no factorisation to update: evaluate each candidate directly
    for (int j = 0; j < n; ++j) scores[j] = ValueAfterAdding(criterion, candidates.Rows(begin + j));
    return;
  }
  if (criterion == Criterion::kO1 || criterion == Criterion::kD) {
    // Π_i (1 + |L_i⁻¹ r_i|²), one log per candidate instead of six; in chunks
    // that stay in cache rather than 7 x W temporaries.
    constexpr int kChunk = 256;
    Eigen::Matrix<double, kParamsPerLeg, kChunk> y;
    Eigen::Array<double, kChunk, 1> growth;
    for (int first = 0; first < n; first += kChunk) {
      const int size = std::min(kChunk, n - first);
      growth.head(size).setOnes();
      for (int i = 0; i < kNumLegs; ++i) {
        y.leftCols(size).noalias() =
            cholesky_inverse_[i].triangularView<Eigen::Lower>() * candidates.legs[i].middleCols(begin + first, size);
        growth.head(size) *= 1 + y.leftCols(size).colwise().squaredNorm().transpose().array();
      }
      for (int j = 0; j < size; ++j) {
        scores[first + j] = FromSpectrum(criterion, log_det_ + std::log(growth[j]), 0, 0, 0, num_poses_ + 1);
      }
    }
    return;
  }
  if (criterion == Criterion::kS) {
    SigmaSumsAfterAdding(inverse_, candidates.legs, begin, n, scores);
    for (int j = 0; j < n; ++j) scores[j] = scores[j] > 0 ? kNumParams / scores[j] : 0.0;
    return;
  }
  if (criterion == Criterion::kA) {
    Eigen::ArrayXd trace = Eigen::ArrayXd::Constant(n, trace_inverse_);
    for (int i = 0; i < kNumLegs; ++i) {
      const auto rows = candidates.legs[i].middleCols(begin, n);
      const Eigen::MatrixXd x = inverse_[i] * rows;
      const Eigen::ArrayXd quadratic = rows.cwiseProduct(x).colwise().sum().transpose().array();
      trace -= x.colwise().squaredNorm().transpose().array() / (1 + quadratic);
    }
    for (int j = 0; j < n; ++j) scores[j] = FromSpectrum(criterion, 0, trace[j], 0, 0, num_poses_ + 1);
    return;
  }
  Eigen::ArrayXd lambda_min = Eigen::ArrayXd::Constant(n, std::numeric_limits<double>::infinity());
  Eigen::ArrayXd lambda_max = Eigen::ArrayXd::Zero(n);
  for (int i = 0; i < kNumLegs; ++i) {
    const Eigen::MatrixXd z = eigenvectors_[i].transpose() * candidates.legs[i].middleCols(begin, n);
    for (int j = 0; j < n; ++j) {
      double smallest, largest;
      RankOneExtremeEigenvalues(eigenvalues_[i], z.col(j), &smallest, &largest);
      lambda_min[j] = std::min(lambda_min[j], smallest);
      lambda_max[j] = std::max(lambda_max[j], largest);
    }
  }
  for (int j = 0; j < n; ++j) scores[j] = FromSpectrum(criterion, 0, 0, lambda_min[j], lambda_max[j], num_poses_ + 1);
}

bool IsEigenvalueCriterion(Criterion criterion) {
  return criterion == Criterion::kO2 || criterion == Criterion::kO3 || criterion == Criterion::kO4 ||
         criterion == Criterion::kE;
}

void DesignState::ScoreUpperBounds(Criterion criterion, const CandidateRows& candidates, int begin, int end,
                                   double* bounds) const {
  const int n = end - begin;
  // λ_min' <= λ_2 of every leg, so a leg whose λ_1 is above the smallest λ_2
  // cannot hold λ_min' and needs no dot product; λ_max' >= the top leg's
  // λ_max + z_7² bounds it below with one leg.
  double smallest_second = std::numeric_limits<double>::infinity();
  int top_leg = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    smallest_second = std::min(smallest_second, eigenvalues_[i][1]);
    if (eigenvalues_[i][kParamsPerLeg - 1] > eigenvalues_[top_leg][kParamsPerLeg - 1]) top_leg = i;
  }
  Eigen::ArrayXd lambda_min = Eigen::ArrayXd::Constant(n, smallest_second);
  for (int i = 0; i < kNumLegs; ++i) {
    if (eigenvalues_[i][0] >= smallest_second) continue;
    const Eigen::RowVectorXd z = eigenvectors_[i].col(0).transpose() * candidates.legs[i].middleCols(begin, n);
    lambda_min = lambda_min.min(eigenvalues_[i][0] + z.array().square().transpose());
  }
  const Eigen::RowVectorXd z_top =
      eigenvectors_[top_leg].col(kParamsPerLeg - 1).transpose() * candidates.legs[top_leg].middleCols(begin, n);
  const Eigen::ArrayXd lambda_max = eigenvalues_[top_leg][kParamsPerLeg - 1] + z_top.array().square().transpose();
  // The exact values come from iterative roots: a relative slack keeps the bound above them.
  constexpr double kSlack = 1e-9;
  for (int j = 0; j < n; ++j) {
    bounds[j] = FromSpectrum(criterion, 0, 0, lambda_min[j] * (1 + kSlack), lambda_max[j] * (1 - kSlack),
                             num_poses_ + 1) * (1 + kSlack);
  }
}

double DesignState::ValueAfterAdding(Criterion criterion, const PoseRows& rows) const {
  std::array<InfoBlock, kNumLegs> blocks = blocks_;
  for (int i = 0; i < kNumLegs; ++i) blocks[i].noalias() += rows[i].transpose() * rows[i];
  return DesignState(blocks, num_poses_ + 1).Value(criterion);
}

double DesignState::ValueAndRowGradient(Criterion criterion, const PoseRows& rows, PoseRows* gradient) const {
  const int m = num_poses_ + 1;
  if ((criterion == Criterion::kO1 || criterion == Criterion::kD) && full_rank_) {
    double log_det = log_det_;
    for (int i = 0; i < kNumLegs; ++i) {
      const Vector7d x = inverse_[i] * rows[i].transpose();
      const double q = rows[i].dot(x.transpose());
      log_det += std::log1p(q);
      (*gradient)[i] = 2 * x.transpose() / (1 + q);  // d log det / d r_i (determinant lemma)
    }
    const double value = FromSpectrum(criterion, log_det, 0, 0, 0, m);
    const double exponent = criterion == Criterion::kO1 ? 2.0 * kNumParams : kNumParams;
    for (JacobianRow& g : *gradient) g *= value / exponent;
    return value;
  }
  if (criterion == Criterion::kA && full_rank_) {
    double trace = trace_inverse_;
    for (int i = 0; i < kNumLegs; ++i) {
      const Vector7d x = inverse_[i] * rows[i].transpose();
      const double q = rows[i].dot(x.transpose()), s = x.squaredNorm();
      trace -= s / (1 + q);
      // d/dr [s / (1 + q)] = 2 M⁻¹x / (1 + q) - 2 s x / (1 + q)²
      (*gradient)[i] = -(2 * inverse_[i] * x / (1 + q) - 2 * s * x / ((1 + q) * (1 + q))).transpose();
    }
    const double value = FromSpectrum(criterion, 0, trace, 0, 0, m);
    for (JacobianRow& g : *gradient) g *= -kNumParams / (trace * trace);
    return value;
  }
  if (criterion == Criterion::kS && full_rank_) {
    const double sum = SigmaSumAfterAddingWithGradient(inverse_, rows, gradient);
    for (JacobianRow& g : *gradient) g *= -kNumParams / (sum * sum);
    return kNumParams / sum;
  }
  // Eigenvalue criteria: dλ/dr = 2 (uᵀr) u for the leg holding the extreme eigenvalue.
  double lambda_min = std::numeric_limits<double>::infinity(), lambda_max = -1;
  int leg_min = 0, leg_max = 0;
  Vector7d u_min = Vector7d::Zero(), u_max = Vector7d::Zero();
  for (int i = 0; i < kNumLegs; ++i) {
    const InfoBlock block = blocks_[i] + rows[i].transpose() * rows[i];
    const Eigen::SelfAdjointEigenSolver<InfoBlock> eigen(block);
    if (eigen.eigenvalues()[0] < lambda_min) {
      lambda_min = eigen.eigenvalues()[0];
      leg_min = i;
      u_min = eigen.eigenvectors().col(0);
    }
    if (eigen.eigenvalues()[kParamsPerLeg - 1] > lambda_max) {
      lambda_max = eigen.eigenvalues()[kParamsPerLeg - 1];
      leg_max = i;
      u_max = eigen.eigenvectors().col(kParamsPerLeg - 1);
    }
  }
  lambda_min = std::max(lambda_min, 1e-300);
  const double value = FromSpectrum(criterion, 0, 0, lambda_min, lambda_max, m);
  double d_min = 0, d_max = 0;  // ∂value/∂λ_min, ∂value/∂λ_max
  switch (criterion) {
    case Criterion::kO2:
      d_min = value / (2 * lambda_min);
      d_max = -value / (2 * lambda_max);
      break;
    case Criterion::kO3: d_min = 0.5 / std::sqrt(lambda_min); break;
    case Criterion::kO4:
      d_min = 1 / std::sqrt(lambda_max);
      d_max = -0.5 * lambda_min / std::pow(lambda_max, 1.5);
      break;
    default: d_min = 1; break;  // E, and D/O1/A on a singular set
  }
  for (JacobianRow& g : *gradient) g.setZero();
  (*gradient)[leg_min] += d_min * 2 * u_min.dot(rows[leg_min].transpose()) * u_min.transpose();
  (*gradient)[leg_max] += d_max * 2 * u_max.dot(rows[leg_max].transpose()) * u_max.transpose();
  return value;
}

double DesignState::ValueAfterRemoving(Criterion criterion, const PoseRows& rows) const {
  std::array<InfoBlock, kNumLegs> blocks = blocks_;
  for (int i = 0; i < kNumLegs; ++i) blocks[i].noalias() -= rows[i].transpose() * rows[i];
  if (criterion == Criterion::kO1 || criterion == Criterion::kD) {
    double log_det = 0;
    for (const InfoBlock& block : blocks) log_det += LogDetOrMinusInfinity(block);
    return FromSpectrum(criterion, log_det, 0, 0, 0, num_poses_ - 1);
  }
  if (criterion == Criterion::kS) {  // RemoveFind's many calls: no eigendecompositions, the same value
    if (const std::optional<double> sigma_sum = SigmaSumIfClearlyFullRank(blocks)) {
      return *sigma_sum > 0 ? kNumParams / *sigma_sum : 0.0;
    }
  }
  return DesignState(blocks, num_poses_ - 1).Value(criterion);
}

void DesignState::Add(const PoseRows& rows) {
  for (int i = 0; i < kNumLegs; ++i) blocks_[i].noalias() += rows[i].transpose() * rows[i];
  ++num_poses_;
  Refactor();
}

void DesignState::Remove(const PoseRows& rows) {
  for (int i = 0; i < kNumLegs; ++i) blocks_[i].noalias() -= rows[i].transpose() * rows[i];
  --num_poses_;
  Refactor();
}

}  // namespace hexcal

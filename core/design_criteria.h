// Design criteria for pose planning and their fast rank-one updates.
//
// A pose contributes one Jacobian row r_i (eq. 5, optionally divided by the
// residual's noise standard deviation) to each leg's 7x7 information block
// M_i. Adding a pose is six rank-one updates, so IOOPS never needs a full
// decomposition per candidate (DESIGN.md):
//   D / O1   log det(M_i + r rᵀ) = log det M_i + log(1 + rᵀ M_i⁻¹ r)   (determinant lemma)
//            rᵀ M_i⁻¹ r = |L_i⁻¹ r|², L_i the Cholesky factor, for a whole
//            candidate batch as one triangular solve
//   A        tr (M + r rᵀ)⁻¹ = tr M⁻¹ - |M⁻¹ r|² / (1 + rᵀ M⁻¹ r)   (Sherman–Morrison)
//   S        (M + r rᵀ)⁻¹_jj = (M⁻¹)_jj - u_j² / (1 + rᵀu), u = M⁻¹ r (sigma_criterion.h)
//   O2-O4, E the extreme eigenvalues of M_i + r rᵀ are roots of the secular
//            equation 1 + Σ_k z_k² / (λ_k - μ) = 0, z = Qᵀ r (Golub 1973)
// Criteria (all maximised), with σ the 42 singular values of J_P:
//   O1..O4  section 2 of the paper;  D = (Π σ²)^(1/42) = det(M)^(1/42);
//   A = 42 / tr(M⁻¹);  E = λ_min(M) = σ_min²;
//   S = 42 / Σ_j √(M⁻¹)_jj, the reciprocal of the mean parameter standard
//       deviation (with noise-weighted rows, in 1 / robot unit).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/identification.h"
#include "core/sigma_criterion.h"

namespace hexcal {

enum class Criterion { kO1, kO2, kO3, kO4, kD, kA, kE, kS };
// The names of the criteria as users type them, in this order: the one table
// ParseCriterion, CriterionName and every option form use.
const std::vector<std::pair<std::string, Criterion>>& CriterionNames();
std::optional<Criterion> ParseCriterion(const std::string& text);
const char* CriterionName(Criterion criterion);

// The six rows one pose adds (row i belongs to leg i).
using PoseRows = std::array<JacobianRow, kNumLegs>;

// Candidate rows stored per leg as 7 x W matrices, for batch scoring.
struct CandidateRows {
  std::array<Eigen::Matrix<double, kParamsPerLeg, Eigen::Dynamic>, kNumLegs> legs;
  int size() const { return static_cast<int>(legs[0].cols()); }
  PoseRows Rows(int j) const;
  void Resize(int count);
  void Set(int j, const PoseRows& rows);
};

// The information of a pose set with the factorisations the updates need.
class DesignState {
 public:
  DesignState(const std::array<InfoBlock, kNumLegs>& blocks, int num_poses);
  static DesignState FromRows(const std::vector<PoseRows>& poses);

  int num_poses() const { return num_poses_; }
  bool full_rank() const { return full_rank_; }
  const std::array<InfoBlock, kNumLegs>& blocks() const { return blocks_; }

  double Value(Criterion criterion) const;
  // Criterion of the set plus candidate j, for every candidate in [begin, end).
  void ScoreAdditions(Criterion criterion, const CandidateRows& candidates, int begin, int end,
                      double* scores) const;
  double ValueAfterAdding(Criterion criterion, const PoseRows& rows) const;
  // For an eigenvalue criterion (O2, O3, O4, E): an upper bound of each
  // candidate's ScoreAdditions value, from the interlacing and Rayleigh bounds
  // of a rank-one update Λ + z zᵀ (z = Qᵀr):
  //   λ_min' <= min(λ_2, λ_1 + z_1²),   λ_max' >= λ_max + z_7²
  // a few dot products instead of twelve secular equations.
  void ScoreUpperBounds(Criterion criterion, const CandidateRows& candidates, int begin, int end,
                        double* bounds) const;
  // Criterion of the set plus one pose and its gradient w.r.t. that pose's six rows.
  double ValueAndRowGradient(Criterion criterion, const PoseRows& rows, PoseRows* gradient) const;
  // Criterion of the set without one of its poses (a downdate, recomputed).
  double ValueAfterRemoving(Criterion criterion, const PoseRows& rows) const;

  void Add(const PoseRows& rows);
  void Remove(const PoseRows& rows);

  // M_i⁻¹ (valid when full_rank()).
  const InfoBlock& inverse(int leg) const { return inverse_[leg]; }

 private:
  void Refactor();
  double FromSpectrum(Criterion criterion, double log_det, double trace_inverse, double lambda_min,
                      double lambda_max, int num_poses) const;

  std::array<InfoBlock, kNumLegs> blocks_;
  int num_poses_ = 0;
  bool full_rank_ = false;
  // Per leg: L⁻¹ (Cholesky), M⁻¹, eigenvectors and ascending eigenvalues.
  std::array<InfoBlock, kNumLegs> cholesky_inverse_, inverse_, eigenvectors_;
  std::array<Eigen::Matrix<double, kParamsPerLeg, 1>, kNumLegs> eigenvalues_;
  double log_det_ = 0, trace_inverse_ = 0, sigma_sum_ = 0;
};

// O2, O3, O4 and E: the criteria on the extreme eigenvalues (secular equation).
bool IsEigenvalueCriterion(Criterion criterion);

// Smallest and largest eigenvalue of diag(lambda) + s z zᵀ, s = +1 or -1, lambda
// ascending; by the secular equation, without forming the matrix.
void RankOneExtremeEigenvalues(const Eigen::Matrix<double, kParamsPerLeg, 1>& lambda,
                               const Eigen::Matrix<double, kParamsPerLeg, 1>& z, double* smallest, double* largest);

}  // namespace hexcal

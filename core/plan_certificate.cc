#include "core/plan_certificate.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/parallel.h"

namespace hexcal {

double PlanCertificate::BestMeanSigma(int num_poses) const {
  return sigma_design.SigmaSumBound() / (kNumParams * std::sqrt(static_cast<double>(num_poses)));
}

namespace {

struct DesignInput {
  CandidateRows candidates;
  DesignState plan;
};

DesignState PlanStateOf(const PlanningModel& model, const std::vector<Vector6d>& plan) {
  std::vector<PoseRows> plan_rows;
  for (const Vector6d& pose : plan) plan_rows.push_back(model.Rows(pose));
  return DesignState::FromRows(plan_rows);
}

// The rows of `candidates`: the first known.size() are `known`'s (rows the
// caller computed already with the same model), the rest computed here.
CandidateRows RowsAfter(const PlanningModel& model, const CandidateRows* known,
                        const std::vector<Vector6d>& candidates) {
  const int reused = known ? std::min<int>(known->size(), candidates.size()) : 0;
  if (reused == 0) return model.RowsOf(candidates);
  const CandidateRows rest =
      model.RowsOf(std::vector<Vector6d>(candidates.begin() + reused, candidates.end()));
  CandidateRows rows;
  rows.Resize(static_cast<int>(candidates.size()));
  for (int i = 0; i < kNumLegs; ++i) {
    rows.legs[i].leftCols(reused) = known->legs[i].leftCols(reused);
    rows.legs[i].rightCols(rest.size()) = rest.legs[i];
  }
  return rows;
}

}  // namespace

StatusOr<PlanCertificate> CertifyPlan(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                                      const std::vector<Vector6d>& plan, const OptimalDesignOptions& options,
                                      const CandidateRows* known_rows) {
  // S is a standard deviation: on weighted rows always, as the S criterion.
  PlanningModel weighted = model;
  if (!weighted.noise) weighted.noise = NoiseModel{};
  const DesignInput d_input{RowsAfter(model, known_rows, candidates), PlanStateOf(model, plan)};
  std::optional<DesignInput> s_own;  // S's own weighted rows, when D's are not
  if (!model.noise) s_own = DesignInput{weighted.RowsOf(candidates), PlanStateOf(weighted, plan)};
  const DesignInput& s_input = s_own ? *s_own : d_input;
  // The two designs are independent and each mostly one thread's work (its
  // working set is small): side by side, one core each when there are two.
  const int threads = ResolveThreadCount(options.threads);
  OptimalDesignOptions each = options;
  each.threads = std::max(1, threads / 2);
  std::optional<StatusOr<OptimalDesign>> design;
  std::optional<StatusOr<SigmaDesign>> sigma_design;
  ParallelFor(2, threads, [&](int k, int /*worker*/) {
    if (k == 0) design = ComputeOptimalDesign(d_input.candidates, each);
    else sigma_design = ComputeSigmaOptimalDesign(s_input.candidates, each);
  });
  if (!design->ok()) return design->status();
  if (!sigma_design->ok()) return sigma_design->status();
  PlanCertificate certificate;
  certificate.design = **design;
  certificate.d_efficiency = DEfficiencyLowerBound(d_input.plan.blocks(), d_input.plan.num_poses(), **design);
  certificate.sigma_design = **sigma_design;
  certificate.s_efficiency =
      SEfficiencyLowerBound(s_input.plan.blocks(), s_input.plan.num_poses(), **sigma_design);
  return certificate;
}

}  // namespace hexcal

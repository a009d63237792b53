#include "core/plan_certificate.h"

#include <cmath>

namespace hexcal {

double PlanCertificate::BestMeanSigma(int num_poses) const {
  return sigma_design.SigmaSumBound() / (kNumParams * std::sqrt(static_cast<double>(num_poses)));
}

namespace {

struct DesignInput {
  CandidateRows candidates;
  DesignState plan;
};

DesignInput RowsOf(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                   const std::vector<Vector6d>& plan) {
  CandidateRows rows = model.RowsOf(candidates);
  std::vector<PoseRows> plan_rows;
  for (const Vector6d& pose : plan) plan_rows.push_back(model.Rows(pose));
  return {std::move(rows), DesignState::FromRows(plan_rows)};
}

}  // namespace

StatusOr<PlanCertificate> CertifyPlan(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                                      const std::vector<Vector6d>& plan, const OptimalDesignOptions& options) {
  PlanCertificate certificate;
  const DesignInput d_input = RowsOf(model, candidates, plan);
  StatusOr<OptimalDesign> design = ComputeOptimalDesign(d_input.candidates, options);
  if (!design.ok()) return design.status();
  certificate.design = *design;
  certificate.d_efficiency = DEfficiencyLowerBound(d_input.plan.blocks(), d_input.plan.num_poses(), *design);
  // S is a standard deviation: on weighted rows always, as the S criterion.
  PlanningModel weighted = model;
  if (!weighted.noise) weighted.noise = NoiseModel{};
  const DesignInput s_input = model.noise ? d_input : RowsOf(weighted, candidates, plan);
  StatusOr<SigmaDesign> sigma_design = ComputeSigmaOptimalDesign(s_input.candidates, options);
  if (!sigma_design.ok()) return sigma_design.status();
  certificate.sigma_design = *sigma_design;
  certificate.s_efficiency = SEfficiencyLowerBound(s_input.plan.blocks(), s_input.plan.num_poses(), *sigma_design);
  return certificate;
}

}  // namespace hexcal

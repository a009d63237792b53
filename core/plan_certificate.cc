#include "core/plan_certificate.h"

#include <cmath>

namespace hexcal {

double PlanCertificate::BestMeanSigma(int num_poses) const {
  return sigma_design.SigmaSumBound() / (kNumParams * std::sqrt(static_cast<double>(num_poses)));
}

StatusOr<PlanCertificate> CertifyPlan(const PlanningModel& model, const std::vector<Vector6d>& candidates,
                                      const std::vector<Vector6d>& plan, const OptimalDesignOptions& options) {
  CandidateRows rows;
  rows.Resize(static_cast<int>(candidates.size()));
  for (size_t j = 0; j < candidates.size(); ++j) rows.Set(static_cast<int>(j), model.Rows(candidates[j]));
  std::vector<PoseRows> plan_rows;
  for (const Vector6d& pose : plan) plan_rows.push_back(model.Rows(pose));
  const DesignState state = DesignState::FromRows(plan_rows);

  PlanCertificate certificate;
  StatusOr<OptimalDesign> design = ComputeOptimalDesign(rows, options);
  if (!design.ok()) return design.status();
  certificate.design = *design;
  certificate.d_efficiency = DEfficiencyLowerBound(state.blocks(), state.num_poses(), *design);
  StatusOr<SigmaDesign> sigma_design = ComputeSigmaOptimalDesign(rows, options);
  if (!sigma_design.ok()) return sigma_design.status();
  certificate.sigma_design = *sigma_design;
  certificate.s_efficiency = SEfficiencyLowerBound(state.blocks(), state.num_poses(), *sigma_design);
  return certificate;
}

}  // namespace hexcal

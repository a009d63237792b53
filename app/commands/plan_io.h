// The pieces of `hexcal plan` around the planner: candidate pools, initial
// sets, plan and history files, the summary.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/ioops.h"

namespace hexcal::cli {

struct CandidatePool {
  std::vector<Vector6d> poses;
  nlohmann::json sources;  // [{"kind": ..., "count": ...}, ...]
};

// From a file, or pooled generated sets (default: one random set). Poses that
// break a measurement constraint are dropped.
StatusOr<CandidatePool> BuildCandidatePool(const PlanningModel& model, const std::string& file,
                                           const std::vector<std::string>& kinds, int count, bool continuous,
                                           uint64_t seed, const std::function<void(int, int)>& progress);

// N starting poses: random | uniform | boundary (N drawn from the boundary set) | a pose CSV.
StatusOr<std::vector<Vector6d>> InitialPoses(const PlanningModel& model, const std::string& init, int count,
                                             uint64_t seed);

Status WritePlanCsv(const std::string& path, const PlanningModel& model, const std::vector<Vector6d>& poses);
Status WriteHistoryCsv(const std::string& path, const PlanResult& plan);

nlohmann::json PlanSummaryJson(const PlannerOptions& options, const PlanResult& plan, const CandidatePool& pool,
                               const nlohmann::json& certificate, const std::string& out);
void PrintPlanSummary(const nlohmann::json& summary, std::ostream& out);

}  // namespace hexcal::cli

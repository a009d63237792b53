// Candidate measurement poses (paper sections 4.1.1 and 6.1).
//   random    uniform in the pose box, kept only if every constraint holds
//   uniform   a Halton low-discrepancy sequence over the pose box, same filter
//   boundary  all 2⁶ combinations of min/max readings, forward kinematics to
//             every real assembly mode, kept if feasible (section 6.1)
// random and uniform need limits.pose_box with all six bounds.
//
//   CandidateOptions options;
//   options.kind = CandidateKind::kBoundary;
//   StatusOr<CandidateSet> set = GenerateCandidates(robot, options);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/job_hooks.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

enum class CandidateKind { kRandom, kUniform, kBoundary };
// The names users type, in this order (the one table for parsing, printing and option forms).
const std::vector<std::pair<std::string, CandidateKind>>& CandidateKindNames();
std::optional<CandidateKind> ParseCandidateKind(const std::string& text);
const char* CandidateKindName(CandidateKind kind);

// More candidates than this is a typo: a pose CSV of about 700 MB.
constexpr int kMaxCandidateCount = 10000000;

struct CandidateOptions {
  CandidateKind kind = CandidateKind::kRandom;
  int count = 1000;                // poses wanted (random, uniform); ignored for boundary
  uint64_t seed = 1;               // random: RNG seed; uniform: Halton sequence offset
  int max_draws_per_pose = 10000;  // give up when acceptance is below 1 / this

  bool IsValid(std::string* error) const;
};

struct CandidateSet {
  std::vector<Vector6d> poses;  // [x, y, z, q1, q2, q3], degrees
  int64_t draws = 0;            // random/uniform: points drawn; boundary: leg combinations
  int real_modes = 0;           // boundary: real assembly modes found over all combinations
};

// hooks.Progress(done, total) now and then; hooks.cancel stops the search
// there (Status::Cancelled).
StatusOr<CandidateSet> GenerateCandidates(const Robot& robot, const CandidateOptions& options,
                                          const JobHooks& hooks = {});

// The readings of stroke corner `corner` (0-63; bit i: leg i at its stroke
// maximum, else its minimum), the combinations the boundary candidates solve.
LegReadings StrokeCornerReadings(const Robot& robot, int corner);

}  // namespace hexcal

#include "core/candidates.h"

#include <random>
#include <sstream>

#include "core/constraints.h"
#include "core/fk_homotopy.h"
#include "core/parallel.h"

namespace hexcal {
namespace {

// Radical inverse of n in a prime base: the Halton sequence's coordinate.
double RadicalInverse(uint64_t n, int base) {
  double inverse = 0, digit_weight = 1.0 / base;
  while (n > 0) {
    inverse += (n % base) * digit_weight;
    n /= base;
    digit_weight /= base;
  }
  return inverse;
}

Status RequireCompleteBox(const Robot& robot, CandidateKind kind) {
  const std::optional<PoseBox> box = robot.limits.SamplingBox();
  if (box && box->IsComplete()) return Status::Ok();
  return Status::BadInput(std::string(CandidateKindName(kind)) + " candidates of robot '" + robot.name +
                          "' need limits.pose_box (or sampling_box) with all of x, y, z, q1, q2, q3");
}

// Draws points in the unit cube from `next_unit` and keeps the feasible ones.
template <typename NextUnit>
StatusOr<CandidateSet> SampleBox(const Robot& robot, const CandidateOptions& options, NextUnit&& next_unit,
                                 const JobHooks& hooks) {
  const PoseBox box = *robot.limits.SamplingBox();
  CandidateSet set;
  const int64_t max_draws = static_cast<int64_t>(options.count) * options.max_draws_per_pose;
  while (static_cast<int>(set.poses.size()) < options.count) {
    if (set.draws >= max_draws) {
      std::ostringstream message;
      message << "only " << set.poses.size() << " of " << set.draws << " poses drawn in the pose box of robot '"
              << robot.name << "' satisfy its constraints; the box or the limits are too tight for " << options.count
              << " candidates";
      return Status::Failed(message.str());
    }
    const Vector6d unit = next_unit();
    ++set.draws;
    Vector6d v;
    for (int k = 0; k < 6; ++k) v[k] = box.bounds[k]->min + unit[k] * (box.bounds[k]->max - box.bounds[k]->min);
    if (!IsFeasible(robot, robot.PoseFromVector(v))) continue;
    set.poses.push_back(v);
    if (set.poses.size() % 256 == 0) {
      if (hooks.Cancelled()) return Status::Cancelled("candidates: cancelled");
      hooks.Progress(static_cast<int>(set.poses.size()), options.count);
    }
  }
  return set;
}

// The 64 min/max leg combinations: one FK family (fk_homotopy.h) solved once,
// then each combination from it on every core, each combination's modes kept
// in its own slot and joined in order, so the set does not depend on the thread count.
StatusOr<CandidateSet> BoundaryCandidates(const Robot& robot, const JobHooks& hooks) {
  constexpr int kCombinations = 64;
  StatusOr<FkFamily> family = FkFamily::ForRobot(robot);
  if (!family.ok()) return family.status();
  std::vector<StatusOr<FkAllResult>> modes(kCombinations, Status::Failed("not computed"));
  const bool finished = ParallelFor(
      kCombinations, 0,
      [&](int combination, int /*worker*/) {
        modes[combination] = family->Solve(StrokeCornerReadings(robot, combination));
      },
      hooks);
  if (!finished) return Status::Cancelled("candidates: cancelled");
  CandidateSet set;
  for (const StatusOr<FkAllResult>& found : modes) {
    if (!found.ok()) return found.status();
    ++set.draws;
    set.real_modes += static_cast<int>(found->poses.size());
    for (const Pose& pose : found->poses) {
      if (IsFeasible(robot, pose)) set.poses.push_back(robot.VectorFromPose(pose));
    }
  }
  return set;
}

}  // namespace

const std::vector<std::pair<std::string, CandidateKind>>& CandidateKindNames() {
  static const std::vector<std::pair<std::string, CandidateKind>> kNames = {
      {"random", CandidateKind::kRandom}, {"uniform", CandidateKind::kUniform}, {"boundary", CandidateKind::kBoundary}};
  return kNames;
}

std::optional<CandidateKind> ParseCandidateKind(const std::string& text) {
  for (const auto& [name, kind] : CandidateKindNames())
    if (text == name) return kind;
  return std::nullopt;
}

const char* CandidateKindName(CandidateKind kind) {
  for (const auto& [name, value] : CandidateKindNames())
    if (value == kind) return name.c_str();
  return "?";
}

bool CandidateOptions::IsValid(std::string* error) const {
  if (kind != CandidateKind::kBoundary && (count < 1 || count > kMaxCandidateCount)) {
    *error = "candidate count must be between 1 and " + std::to_string(kMaxCandidateCount) + ", got " +
             std::to_string(count);
    return false;
  }
  if (max_draws_per_pose < 1) {
    *error = "max_draws_per_pose must be positive";
    return false;
  }
  return true;
}

LegReadings StrokeCornerReadings(const Robot& robot, int corner) {
  LegReadings readings;
  for (int i = 0; i < kNumLegs; ++i) {
    readings[i] = (corner >> i) & 1 ? robot.legs[i].stroke_max : robot.legs[i].stroke_min;
  }
  return readings;
}

StatusOr<CandidateSet> GenerateCandidates(const Robot& robot, const CandidateOptions& options, const JobHooks& hooks) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput(error);
  if (options.kind == CandidateKind::kBoundary) return BoundaryCandidates(robot, hooks);
  if (Status box = RequireCompleteBox(robot, options.kind); !box.ok()) return box;

  if (options.kind == CandidateKind::kRandom) {
    std::mt19937_64 rng(options.seed);
    std::uniform_real_distribution<double> unit(0, 1);
    return SampleBox(
        robot, options,
        [&] {
          Vector6d u;
          for (int k = 0; k < 6; ++k) u[k] = unit(rng);
          return u;
        },
        hooks);
  }
  static constexpr int kPrimes[6] = {2, 3, 5, 7, 11, 13};
  uint64_t index = 1 + options.seed * 1000003ULL % 1000000007ULL;  // skip the origin; seed shifts the sequence
  return SampleBox(
      robot, options,
      [&] {
        Vector6d u;
        for (int k = 0; k < 6; ++k) u[k] = RadicalInverse(index, kPrimes[k]);
        ++index;
        return u;
      },
      hooks);
}

}  // namespace hexcal

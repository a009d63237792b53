#include "core/reflector_estimate.h"

#include <algorithm>
#include <map>

#include "core/point_fit.h"

namespace hexcal {
namespace {

constexpr int kMaxRounds = 50;

// The set's points whose names the estimate has.
std::vector<NamedPoint> SharedPoints(const std::vector<NamedPoint>& estimate, const std::vector<NamedPoint>& set) {
  std::vector<NamedPoint> shared;
  for (const NamedPoint& point : set) {
    const bool known = std::any_of(estimate.begin(), estimate.end(),
                                   [&](const NamedPoint& r) { return r.name == point.name; });
    if (known) shared.push_back(point);
  }
  return shared;
}

// One round: every fitting set mapped into the estimate's frame, averaged by
// name (in the order names first appear).
std::vector<NamedPoint> AverageRound(const std::vector<NamedPoint>& estimate, const PointSets& sets) {
  std::map<std::string, std::pair<Eigen::Vector3d, int>> sums;
  std::vector<std::string> order;
  for (const PointSet& set : sets) {
    const std::vector<NamedPoint> shared = SharedPoints(estimate, set.points);
    if (shared.size() < 3) continue;
    StatusOr<PointFit> fit = FitPointPose(estimate, shared);
    if (!fit.ok()) continue;
    const Pose& pose = fit->pose;  // tracker_from_reflectors
    for (const NamedPoint& point : set.points) {
      auto [it, added] = sums.try_emplace(point.name, Eigen::Vector3d::Zero(), 0);
      if (added) order.push_back(point.name);
      it->second.first += pose.rotation.transpose() * (point.position - pose.position);
      ++it->second.second;
    }
  }
  std::vector<NamedPoint> average;
  for (const std::string& name : order) average.push_back({name, sums[name].first / sums[name].second, 0});
  return average;
}

// The largest distance a reflector moved between two estimates, and the size
// of the estimate (its largest distance from the first point).
double LargestMove(const std::vector<NamedPoint>& before, const std::vector<NamedPoint>& after, double* size) {
  double move = 0;
  *size = 0;
  for (const NamedPoint& point : after) {
    *size = std::max(*size, (point.position - after.front().position).norm());
    const auto old = std::find_if(before.begin(), before.end(), [&](const NamedPoint& r) { return r.name == point.name; });
    move = std::max(move, old == before.end() ? *size + 1 : (point.position - old->position).norm());
  }
  return move;
}

}  // namespace

StatusOr<std::vector<NamedPoint>> EstimateReflectors(const PointSets& sets) {
  const auto largest = std::max_element(sets.begin(), sets.end(), [](const PointSet& a, const PointSet& b) {
    return a.points.size() < b.points.size();
  });
  if (largest == sets.end() || largest->points.size() < 3)
    return Status::BadInput("no pose has 3 or more points: the reflectors cannot be estimated (give a reflector file)");
  std::vector<NamedPoint> estimate = largest->points;
  for (NamedPoint& point : estimate) point.sigma = 0;
  for (int round = 0; round < kMaxRounds; ++round) {
    std::vector<NamedPoint> next = AverageRound(estimate, sets);
    if (next.size() < 3) break;
    double size = 0;
    const double move = LargestMove(estimate, next, &size);
    estimate = std::move(next);
    if (move <= 1e-9 * size) break;
  }
  return estimate;
}

}  // namespace hexcal

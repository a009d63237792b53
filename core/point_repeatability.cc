#include "core/point_repeatability.h"

#include <cmath>

#include "core/point_fit.h"
#include "core/reflector_estimate.h"

namespace hexcal {

StatusOr<Repeatability> MeasurePointRepeatability(const PointSets& sets) {
  if (sets.size() < 3)
    return Status::BadInput(std::to_string(sets.size()) + " point sets: the repeatability needs 3 or more of one pose");
  StatusOr<std::vector<NamedPoint>> shape = EstimateReflectors(sets);
  if (!shape.ok()) return shape.status();
  double residual_squares = 0, sigma_squares = 0;
  int observed = 0;
  for (const PointSet& set : sets) {
    StatusOr<PointFit> fit = FitPointPose(*shape, set.points);
    if (!fit.ok()) return Status::BadInput("set '" + set.pose + "': " + fit.status().message());
    for (double r : fit->residuals) residual_squares += r * r;
    for (const NamedPoint& point : set.points) sigma_squares += point.sigma * point.sigma;
    observed += static_cast<int>(set.points.size());
  }
  Repeatability result;
  result.repeats = static_cast<int>(sets.size());
  result.points = static_cast<int>(shape->size());
  result.degrees_of_freedom = 3 * observed - 6 * result.repeats - 3 * result.points + 6;
  if (result.degrees_of_freedom < 1)
    return Status::BadInput("too few points for a repeatability: measure more sets of the same pose");
  result.measured_sigma = std::sqrt(residual_squares / result.degrees_of_freedom);
  result.declared_sigma = std::sqrt(sigma_squares / observed);
  result.ratio = result.measured_sigma / result.declared_sigma;
  return result;
}

}  // namespace hexcal

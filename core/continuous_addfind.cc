#include "core/continuous_addfind.h"

#include <nlopt.hpp>

#include <cmath>
#include <limits>
#include <optional>

#include "core/parallel.h"

namespace hexcal {
namespace {

struct SearchContext {
  const PlanningModel* model;
  const DesignState* state;
  Criterion criterion;
  int evaluations = 0;
};

Vector6d ToVector(const double* x) { return Eigen::Map<const Vector6d>(x); }

double Objective(unsigned n, const double* x, double* grad, void* data) {
  auto* context = static_cast<SearchContext*>(data);
  ++context->evaluations;
  Vector6d gradient;
  const double value = CriterionAndGradient(*context->model, *context->state, context->criterion, ToVector(x), &gradient);
  if (grad) {
    for (unsigned k = 0; k < n; ++k) grad[k] = gradient[k];
  }
  return value;
}

// NLopt wants c(x) <= 0: c = -margin. Gradients by central differences.
void Constraints(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  auto* context = static_cast<SearchContext*>(data);
  const Vector6d pose = ToVector(x);
  const std::vector<double> margins = context->model->Margins(pose, /*include_box=*/false);
  for (unsigned c = 0; c < m; ++c) result[c] = -margins[c];
  if (!grad) return;
  for (unsigned k = 0; k < n; ++k) {
    const double h = 1e-6 * (1 + std::abs(x[k]));
    Vector6d plus = pose, minus = pose;
    plus[k] += h;
    minus[k] -= h;
    const std::vector<double> mp = context->model->Margins(plus, false), mm = context->model->Margins(minus, false);
    for (unsigned c = 0; c < m; ++c) grad[c * n + k] = -(mp[c] - mm[c]) / (2 * h);
  }
}

}  // namespace

double CriterionAndGradient(const PlanningModel& model, const DesignState& state, Criterion criterion,
                            const Vector6d& pose, Vector6d* gradient) {
  PoseRows row_gradient;
  const double value = state.ValueAndRowGradient(criterion, model.Rows(pose), &row_gradient);
  const auto jacobians = model.RowJacobians(pose);
  gradient->setZero();
  for (int i = 0; i < kNumLegs; ++i) *gradient += jacobians[i].transpose() * row_gradient[i].transpose();
  return value;
}

namespace {

// An angle the pose box leaves unbounded winds freely under SLSQP (to 10⁵
// degrees on the INRIA robot without its yaw bound): give it back in
// [-180, 180], the same rotation.
Vector6d WrapFreeAngles(Vector6d pose, const std::vector<double>& lower, const std::vector<double>& upper) {
  for (int k = 3; k < 6; ++k) {
    if (std::isinf(lower[k]) && std::isinf(upper[k])) pose[k] = std::remainder(pose[k], 360.0);
  }
  return pose;
}

// The local maximisation from one start: its optimum when that is feasible.
std::optional<ContinuousResult> MaximiseFrom(const PlanningModel& model, const DesignState& state, Criterion criterion,
                                             const Vector6d& start, const std::vector<double>& lower,
                                             const std::vector<double>& upper, unsigned constraint_count,
                                             int max_evaluations) {
  SearchContext context{&model, &state, criterion};
  nlopt::opt optimizer(nlopt::LD_SLSQP, 6);
  optimizer.set_lower_bounds(lower);
  optimizer.set_upper_bounds(upper);
  optimizer.set_max_objective(Objective, &context);
  optimizer.add_inequality_mconstraint(Constraints, &context, std::vector<double>(constraint_count, 1e-9));
  optimizer.set_xtol_rel(1e-9);
  optimizer.set_ftol_rel(1e-10);
  optimizer.set_maxeval(max_evaluations);
  std::vector<double> x(start.data(), start.data() + 6);
  for (int k = 0; k < 6; ++k) x[k] = std::min(std::max(x[k], lower[k]), upper[k]);
  double value = 0;
  try {
    optimizer.optimize(x, value);
  } catch (const std::exception&) {
    // SLSQP stops with roundoff or a failed line search now and then; x holds its last iterate.
  }
  const Vector6d pose = WrapFreeAngles(ToVector(x.data()), lower, upper);
  if (!pose.allFinite() || !model.IsFeasible(pose)) return std::nullopt;
  Vector6d unused;
  return ContinuousResult{pose, CriterionAndGradient(model, state, criterion, pose, &unused)};
}

}  // namespace

std::vector<ContinuousResult> ContinuousAddFind(const PlanningModel& model, const DesignState& state,
                                                Criterion criterion, const std::vector<Vector6d>& starts,
                                                int max_evaluations, int threads) {
  std::vector<ContinuousResult> results;
  if (starts.empty()) return results;
  const unsigned constraint_count = static_cast<unsigned>(model.Margins(starts.front(), false).size());
  std::vector<double> lower(6, -std::numeric_limits<double>::infinity()), upper(6, std::numeric_limits<double>::infinity());
  if (model.robot.limits.pose_box) {
    for (int k = 0; k < 6; ++k) {
      if (const auto& range = model.robot.limits.pose_box->bounds[k]) {
        lower[k] = range->min;
        upper[k] = range->max;
      }
    }
  }
  // The starts are independent: one slot each, joined in order, so the
  // results do not depend on the thread count.
  std::vector<std::optional<ContinuousResult>> found(starts.size());
  ParallelFor(static_cast<int>(starts.size()), threads, [&](int k, int /*worker*/) {
    found[k] = MaximiseFrom(model, state, criterion, starts[k], lower, upper, constraint_count, max_evaluations);
  });
  for (const std::optional<ContinuousResult>& result : found) {
    if (result) results.push_back(*result);
  }
  return results;
}

}  // namespace hexcal

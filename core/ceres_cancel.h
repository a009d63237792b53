// The one Ceres iteration callback that stops a solve when a job's cancel
// flag is raised (core/job_hooks.h): the solve then ends as USER_FAILURE at
// its next iteration. For .cc files that link Ceres (core's calibration,
// vision's calibration from pixels); core's public headers do not include Ceres.
//
//   CeresCancelCallback cancel(hooks);
//   if (hooks.cancel != nullptr) solver_options.callbacks.push_back(&cancel);
#pragma once

#include <ceres/iteration_callback.h>

#include "core/job_hooks.h"

namespace hexcal {

class CeresCancelCallback final : public ceres::IterationCallback {
 public:
  explicit CeresCancelCallback(const JobHooks& hooks) : hooks_(hooks) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return hooks_.Cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const JobHooks& hooks_;
};

}  // namespace hexcal

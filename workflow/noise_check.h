// `hexcal session check-noise` (issue 38; docs/session.md, "Repeatability
// check"): one pose measured k times, the scatter against the noise the
// session declares, for either instrument:
// - points: k point sets of the same reflectors (core/point_repeatability.h);
//   declared: the points' σ (the file's, else session.yaml's point_sigma);
// - camera: k images of the board, the platform not moved; declared: each
//   board pose's covariance (vision/board_pose.h), the scatter that of the
//   six pose coordinates about their mean.
// The ratio measured/declared is judged: within 20 % good; above, the
// declared noise is optimistic and the calibration of a points session scales
// its fits' covariances by the ratio (SessionNoiseFactor); below, pessimistic.
// The result is kept in DIR/noise_check.json, an input of the calibration.
//
//   StatusOr<NoiseCheck> check = CheckSessionNoise({"run1", "repeats.txt"}, hooks);
//   std::cout << FormatNoiseCheck(*check);
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/job_hooks.h"
#include "core/point_repeatability.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/status.h"
#include "workflow/point_session.h"

namespace hexcal::workflow {

constexpr double kNoiseRatioTolerance = 0.2;                 // |ratio − 1| within it: good

struct NoiseCheckRequest {
  std::string session;
  std::string input;  // points sessions: a points file of k sets; camera sessions: a folder of k images
  LockWait wait = LockWait::kNo;
};

struct NoiseCheck {
  Instrument instrument = Instrument::kCamera;
  Repeatability figures;  // camera: σ of the position coordinates (target unit), ratio over all six
  std::string unit;       // of the σ
  std::string judgement;  // "good", "optimistic" (ratio above 1.2) or "pessimistic" (below 0.8)
};

StatusOr<NoiseCheck> CheckSessionNoise(const NoiseCheckRequest& request, const JobHooks& hooks = {});

nlohmann::json ToJson(const NoiseCheck& check);
std::string FormatNoiseCheck(const NoiseCheck& check);

}  // namespace hexcal::workflow

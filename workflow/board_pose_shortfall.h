// Why a session's images give fewer board poses than the registration needs
// (3): how many images ended in each status, a few of their names, and, for
// the first image that shows none of the target's tags, what it holds instead
// (another border width or family, vision/layout_hint.h). Without this the
// calibration stopped at "registration needs at least 3 poses, got 0".
//
//   if (ok < kMinBoardPoses) return Status::BadInput(dir + ": " + ExplainBoardPoseShortfall(dir, poses, target));
#pragma once

#include <map>
#include <string>

#include "vision/target.h"
#include "workflow/session_measure.h"

namespace hexcal::workflow {

// The registration's minimum (core/registration.h).
constexpr int kMinBoardPoses = 3;

// `poses`: by image file name, as MeasureSessionImages gives them.
std::string ExplainBoardPoseShortfall(const std::string& dir, const std::map<std::string, SessionImagePose>& poses,
                                      const Target& target);

}  // namespace hexcal::workflow

// The planning model a session implies (`hexcal plan --session`, the GUI's
// Plan panel; docs/planner.md, "Planning for a laser tracker"): its robot and
// noise model and, for a points session with a reflector file, the tracker
// (core/tracker_model.h): each pose weighted by the covariance the tracker
// measures it with (σ per reflector, growing with its distance under
// `tracker.sigma_law: linear`), and with `tracker.position` every reflector in
// the tracker's line of sight. The reflectors are taken in the platform frame
// until a calibration has registered their frame (session.yaml's
// frames.platform_from_target), then through it.
//
//   StatusOr<PlanningModel> model = SessionPlanningModel("run1");
#pragma once

#include <string>

#include "core/planning_model.h"
#include "core/session.h"
#include "core/status.h"

namespace hexcal::workflow {

// From the folder's session.yaml; bad input naming the file and key when the
// robot or the reflector file does not load, or a tracker section has no
// reflector file to plan with.
StatusOr<PlanningModel> SessionPlanningModel(const std::string& dir);
// The same from a configuration and robot already loaded.
StatusOr<PlanningModel> SessionPlanningModel(const std::string& dir, const SessionConfig& config, const Robot& robot);

}  // namespace hexcal::workflow

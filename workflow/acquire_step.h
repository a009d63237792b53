// The Acquire step (issue 16, docs/acquisition.md): drive the robot to each
// planned pose, let it settle, grab a frame and read the six legs, and record
// image and readings in the session together (workflow/session_edits.h,
// RecordCaptureBytes), one pose at a time. The CLI (`hexcal acquire`) runs a
// whole plan; the GUI's Acquire step may run the plan or single poses.
//
// Pose k of the plan is recorded as images/pose_000k.png with its legs.csv
// row. A run resumes where an earlier one stopped, however it stopped
// (cancel, kill, power loss): poses whose row is in legs.csv are skipped, and
// an image left without its row by a kill between the two writes is recorded
// again. A pose that fails (unreachable, no frame) is reported and the run
// goes on; the next run tries it again.
//
//   StatusOr<AcquisitionRig> rig = OpenAcquisitionRig("run1", "sim", "sim", /*seed=*/1);
//   StatusOr<PoseRecord> one = AcquirePose("run1", 7, pose, *rig->controller, *rig->camera, {}, hooks);
//
//   AcquireRequest request{"run1"};  // controller and camera "sim", SESSION/plan.csv
//   StatusOr<AcquireResult> run = AcquirePlan(request, hooks);
//   if (run.ok()) std::cout << FormatAcquireSummary(*run);
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/job_hooks.h"
#include "core/pose.h"
#include "core/session_lock.h"
#include "core/status.h"
#include "devices/controller.h"
#include "devices/device_urls.h"
#include "devices/frame_source.h"
#include "workflow/acquire_options.h"
#include "workflow/plan_captures.h"

namespace hexcal::workflow {

class SimWorld;

enum class PoseState { kRecorded, kAlreadyRecorded, kFailed };
const char* PoseStateName(PoseState state);  // "recorded", "already recorded", "failed"

struct PoseRecord {
  int index = 0;  // row of the plan, from 0
  PoseState state = PoseState::kRecorded;
  std::string image;                           // "pose_0007.png"
  Vector6d pose = Vector6d::Zero();            // as commanded: robot unit, degrees
  LegReadings readings = LegReadings::Zero();  // as recorded (kRecorded only), robot unit
  bool holdout = false;
  double seconds = 0;  // move, settle, grab and record
  std::string error;   // kFailed: why
};

// AcquiredImageName ("pose_0007.png") and the names of captures after a new
// plan are in workflow/plan_captures.h.

// One pose: move, settle, grab, read the legs, check them (reading_check.h),
// record. Errors: the pose's own (unreachable: bad input; no frame, FK:
// failed), readings refused (failed; nothing recorded), a cancel (checked
// between the move and the grab), a busy session, a write that failed, or a
// row that exists already (bad input: the pose is recorded).
StatusOr<PoseRecord> AcquirePose(const std::string& session_dir, int pose_index, const Vector6d& pose,
                                 Controller& controller, FrameSource& camera, const AcquireOptions& options,
                                 const JobHooks& hooks = {});

// The controller and camera of one run. `sim` URLs share one SimWorld,
// whose hidden truth is written to SESSION/truth/ (and must match a truth
// there already: resume with the same seed). An empty camera URL opens none:
// a points session's rig (its sim world then also stands behind the sim
// tracker, point_demo_scene.h).
struct AcquisitionRig {
  std::shared_ptr<SimWorld> sim;  // null without `sim` URLs
  std::unique_ptr<Controller> controller;
  std::unique_ptr<FrameSource> camera;  // null for an empty camera URL
};
// What a `sim` rig does with its hidden truth: write it into SESSION/truth/
// (or check it against the one there: acquire), or only check it against one
// there (verify, which writes nothing into the session).
enum class TruthRecord { kWriteOrCheck, kCheckOnly };
StatusOr<AcquisitionRig> OpenAcquisitionRig(const std::string& session_dir, const std::string& controller_url,
                                            const std::string& camera_url, uint64_t seed,
                                            TruthRecord truth = TruthRecord::kWriteOrCheck);

struct AcquireRequest {
  std::string session;
  std::string controller = "sim";  // URL, devices/controller.h
  std::string camera = "sim";      // URL, devices/frame_source.h
  std::string poses{};             // pose CSV; empty: SESSION/plan.csv
  uint64_t seed = 1;               // of the sim world's truth and noise
  AcquireOptions options{};
};

struct AcquireResult {
  std::string session, controller, camera;  // the folder and the devices' Describe()
  std::vector<PoseRecord> poses;            // one per plan row, in plan order
  double seconds = 0;                       // the whole run
  double settle_seconds = 0;                // waited after each move
  std::vector<int> visit_order;             // the plan rows in the order they were visited

  int Count(PoseState state) const;
};

// Runs the plan with the devices of the request's URLs (OpenAcquisitionRig).
// Holds the session lock throughout. The poses not recorded yet are visited
// nearest first (VisitOrder), so that moves are short. Stage "acquire",
// progress per pose, a note per pose. A cancel returns Status::Cancelled;
// readings refused stop the run with their error (failed); what was recorded
// stays.
StatusOr<AcquireResult> AcquirePlan(const AcquireRequest& request, const JobHooks& hooks = {});
// The same with devices the caller opened (the GUI keeps its connection).
StatusOr<AcquireResult> AcquirePlan(const AcquireRequest& request, Controller& controller, FrameSource& camera,
                                    const JobHooks& hooks = {});

// The order of the plan rows not in `skip`: from `start`, each time the
// nearest pose left, in leg space with each leg's change divided by its
// stroke (what the moves between them have to cover).
std::vector<int> VisitOrder(const Robot& robot, const std::vector<Vector6d>& poses, const Vector6d& start,
                            const std::vector<bool>& skip);

nlohmann::json ToJson(const AcquireResult& result);
std::string FormatAcquireSummary(const AcquireResult& result);

}  // namespace hexcal::workflow

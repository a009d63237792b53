#include "workflow/acquire_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "session/readings_table.h"
#include "sim/sim_world.h"
#include "vision/image_codecs.h"
#include "workflow/acquire_files.h"
#include "workflow/plan_captures.h"
#include "workflow/reading_check.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_edits.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Move, settle, grab, read: the device half of AcquirePose.
Status DriveAndCapture(const Vector6d& pose, Controller& controller, FrameSource& camera, const AcquireOptions& options,
                       const JobHooks& hooks, cv::Mat* frame, LegReadings* readings) {
  if (Status s = controller.MoveTo(pose); !s.ok()) return s;
  const double settle = options.settle_seconds.value_or(controller.DefaultSettleSeconds());
  if (Status s = controller.WaitSettled(settle); !s.ok()) return s;
  if (hooks.Cancelled()) return Status::Cancelled();
  StatusOr<cv::Mat> grabbed = camera.Grab(std::chrono::milliseconds(options.grab_timeout_ms));
  if (!grabbed.ok()) return grabbed.status();
  StatusOr<LegReadings> legs = controller.ReadLegs();
  if (!legs.ok()) return legs.status();
  *frame = std::move(*grabbed);
  *readings = *legs;
  return Status::Ok();
}

// The caller's cancel flag reaches the controller's waits while a pose is
// acquired, so that Ctrl-C stops a move rather than waiting for its end.
class CancelFlagLent {
 public:
  CancelFlagLent(Controller& controller, const JobHooks& hooks) : controller_(controller) {
    controller_.SetCancelFlag(hooks.cancel);
  }
  ~CancelFlagLent() { controller_.SetCancelFlag(nullptr); }
  CancelFlagLent(const CancelFlagLent&) = delete;
  CancelFlagLent& operator=(const CancelFlagLent&) = delete;

 private:
  Controller& controller_;
};

// Errors that stop the whole run rather than one pose.
bool StopsTheRun(const Status& status) {
  return status.cancelled() || status.kind() == StatusKind::kBusy || status.kind() == StatusKind::kIo;
}

StatusOr<std::vector<Vector6d>> LoadRequestedPoses(const AcquireRequest& request) {
  const std::string path = request.poses.empty() ? SessionPaths(request.session).plan : request.poses;
  std::error_code error;
  if (request.poses.empty() && !fs::exists(fs::symlink_status(path, error)))  // a dangling link is named by LoadPoses
    return Status::BadInput(path + ": no plan in the session; run hexcal plan --out " + path + " or pass --poses FILE");
  return LoadPoses(path);
}

// The image name a new capture of plan row `pose_index` gets
// (CaptureImageName); an error when the pose is recorded already, or an
// operator's file is where the image would go (ClearImageSlot, which removes
// the image a killed capture left when `remove`).
StatusOr<std::string> FreeCaptureName(const std::string& dir, const ReadingCheck& check, int pose_index,
                                      const Vector6d& pose, const JobHooks& hooks, bool remove) {
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(dir);
  if (!rows.ok()) return rows.status();
  if (const int row = CaptureOfPose(check, pose_index, pose, *rows); row >= 0)
    return Status::BadInput(dir + ": " + (*rows)[row].image + " is recorded already");
  const std::string image = CaptureImageName(pose_index, *rows);
  if (Status s = ClearImageSlot(dir, image, remove, hooks); !s.ok()) return s;
  return image;
}

// AcquirePose; *refused (if given) says the controller's readings were refused.
StatusOr<PoseRecord> AcquireOnePose(const std::string& dir, int pose_index, const Vector6d& pose,
                                    Controller& controller, FrameSource& camera, const AcquireOptions& options,
                                    const JobHooks& hooks, bool* refused) {
  const auto start = std::chrono::steady_clock::now();
  // Read before the machine moves: a session whose robot cannot be loaded is
  // refused before anything moves.
  StatusOr<ReadingCheck> check = SessionReadingCheck(dir);
  if (!check.ok()) return check.status();
  PoseRecord record;
  record.index = pose_index;
  record.pose = pose;
  record.holdout = options.holdout_every > 0 && pose_index % options.holdout_every == options.holdout_every - 1;
  // A recorded pose (by the pose its row was commanded to, plan_captures.h),
  // or an operator's own file where the image would go: refused before the
  // machine moves (and again under the lock, below).
  StatusOr<std::string> image = FreeCaptureName(dir, *check, pose_index, pose, hooks, false);
  if (!image.ok()) return image.status();
  record.image = *image;
  cv::Mat frame;
  const CancelFlagLent lent(controller, hooks);
  if (Status s = DriveAndCapture(pose, controller, camera, options, hooks, &frame, &record.readings); !s.ok()) return s;
  if (Status s = CheckReadings(*check, record.image, pose, record.readings); !s.ok()) {
    if (refused) *refused = true;
    return Status::Failed(controller.Describe() + ": " + s.message());
  }
  StatusOr<std::string> png = EncodePng(frame);  // lossless: the corners are measured in it
  if (!png.ok()) return png.status().Prefixed(record.image + ": ");

  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, options.wait);
  if (!lock.ok()) return lock.status();
  image = FreeCaptureName(dir, *check, pose_index, pose, hooks, true);
  if (!image.ok()) return image.status();
  record.image = *image;
  LegsRow row;
  row.image = record.image;
  row.legs = record.readings;
  row.holdout = record.holdout;
  row.commanded = pose;
  if (Status s = RecordWithPendingName(dir, *png, row, options.wait); !s.ok()) return s;
  record.seconds = SecondsSince(start);
  return record;
}

// One plan row: skipped when recorded, else acquired; a failure is recorded
// in the result unless it stops the run.
StatusOr<PoseRecord> RunOnePose(const AcquireRequest& request, const PoseRecord& planned, Controller& controller,
                                FrameSource& camera, const JobHooks& hooks) {
  if (planned.state == PoseState::kAlreadyRecorded) return planned;
  const int index = planned.index;
  const Vector6d& pose = planned.pose;
  bool refused = false;
  StatusOr<PoseRecord> done =
      AcquireOnePose(request.session, index, pose, controller, camera, request.options, hooks, &refused);
  // Readings refused mean a controller that cannot be trusted: the next
  // pose's would not be either. A machine stuck in a move (a time-out, a stop
  // away from the target) would fail every later pose the same way.
  if (done.ok() || refused || StopsTheRun(done.status())) return done;
  if (!controller.Usable())
    return Status::Failed(done.status().message() + "; the run stops here: look at the machine, then run " +
                          "hexcal acquire again to go on");
  PoseRecord failed = planned;
  failed.state = PoseState::kFailed;
  failed.error = done.status().message();
  return failed;
}

std::string PoseNote(const PoseRecord& record, int total) {
  std::ostringstream line;
  line << "pose " << record.index + 1 << "/" << total << " " << record.image << ": " << PoseStateName(record.state);
  if (record.state == PoseState::kRecorded)
    line << " in " << FormatNumber(std::round(record.seconds * 100) / 100) << " s";
  if (record.state == PoseState::kFailed) line << ": " << record.error;
  return line.str();
}

StatusOr<Robot> LoadSessionRobot(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  return workflow::LoadSessionRobot(dir, *config);
}

// The sim truth is written once; a resumed run must draw the same truth.
Status WriteOrCheckTruth(const SimWorld& world, const std::string& dir, uint64_t seed, TruthRecord truth) {
  const std::string robot_file = (fs::path(dir) / "truth" / "robot.yaml").string();
  std::error_code error;
  if (!fs::exists(robot_file, error)) return truth == TruthRecord::kWriteOrCheck ? world.WriteTruth(dir) : Status::Ok();
  StatusOr<std::string> on_disk = ReadFileToString(robot_file, kMaxTableBytes);
  if (!on_disk.ok()) return on_disk.status();
  if (*on_disk != RobotToYaml(world.scene().truth))
    return Status::BadInput(robot_file + ": the session's sim truth was drawn with another --seed than " +
                            std::to_string(seed) + "; resume with the seed of the first run");
  return Status::Ok();
}

}  // namespace

const char* PoseStateName(PoseState state) {
  switch (state) {
    case PoseState::kRecorded:
      return "recorded";
    case PoseState::kAlreadyRecorded:
      return "already recorded";
    case PoseState::kFailed:
      return "failed";
  }
  return "?";
}

int AcquireResult::Count(PoseState state) const {
  int count = 0;
  for (const PoseRecord& record : poses) count += record.state == state;
  return count;
}

StatusOr<PoseRecord> AcquirePose(const std::string& dir, int pose_index, const Vector6d& pose, Controller& controller,
                                 FrameSource& camera, const AcquireOptions& options, const JobHooks& hooks) {
  return AcquireOnePose(dir, pose_index, pose, controller, camera, options, hooks, nullptr);
}

StatusOr<AcquisitionRig> OpenAcquisitionRig(const std::string& dir, const std::string& controller_url,
                                            const std::string& camera_url, uint64_t seed, TruthRecord truth) {
  AcquisitionRig rig;
  const bool sim = controller_url == "sim" || camera_url == "sim";
  if (camera_url == "sim" && controller_url != "sim")
    return Status::BadInput("camera 'sim' renders the sim world's platform: it needs --controller sim");
  if (sim) {
    StatusOr<std::shared_ptr<SimWorld>> world = SimWorld::ForSession(dir, seed);
    if (!world.ok()) return world.status();
    rig.sim = *world;
  }
  // The camera first: a bad camera URL is refused before a real machine is
  // powered on and homed.
  // No camera URL: a points session's rig, whose poses the tracker measures.
  StatusOr<std::unique_ptr<FrameSource>> camera =
      camera_url.empty() ? std::unique_ptr<FrameSource>() : OpenFrameSource(camera_url, SimFrameSourceOptions(rig.sim));
  if (!camera.ok()) return camera.status();
  ControllerOptions controller_options = SimControllerOptions(rig.sim);
  if (controller_url != "sim") {  // a real machine converts poses and joints with the session's robot
    StatusOr<Robot> robot = LoadSessionRobot(dir);
    if (!robot.ok()) return robot.status();
    controller_options.robot = std::make_shared<const Robot>(std::move(*robot));
  }
  StatusOr<std::unique_ptr<Controller>> controller = OpenController(controller_url, controller_options);
  if (!controller.ok()) return controller.status();
  rig.controller = std::move(*controller);
  rig.camera = std::move(*camera);
  if (sim) {  // the truth is written only for a rig that opened whole
    StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kBriefly);
    if (!lock.ok()) return lock.status();
    if (Status s = WriteOrCheckTruth(*rig.sim, dir, seed, truth); !s.ok()) return s;
  }
  return rig;
}

StatusOr<AcquireResult> AcquirePlan(const AcquireRequest& request, const JobHooks& hooks) {
  if (Status s = request.options.Check(); !s.ok()) return s;
  // The plan and the session are checked before a sim world writes its truth
  // into the session, or a machine is powered on and homed.
  if (StatusOr<std::vector<Vector6d>> poses = LoadRequestedPoses(request); !poses.ok()) return poses.status();
  if (Status s = CheckSessionTakesCaptures(request.session); !s.ok()) return s;
  if (StatusOr<Robot> robot = LoadSessionRobot(request.session); !robot.ok()) return robot.status();
  StatusOr<AcquisitionRig> rig = OpenAcquisitionRig(request.session, request.controller, request.camera, request.seed);
  if (!rig.ok()) return rig.status();
  return AcquirePlan(request, *rig->controller, *rig->camera, hooks);
}

StatusOr<AcquireResult> AcquirePlan(const AcquireRequest& request, Controller& controller, FrameSource& camera,
                                    const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  if (Status s = request.options.Check(); !s.ok()) return s;
  StatusOr<std::vector<Vector6d>> poses = LoadRequestedPoses(request);
  if (!poses.ok()) return poses.status();
  StatusOr<Robot> robot = LoadSessionRobot(request.session);
  if (!robot.ok()) return robot.status();
  StatusOr<SessionLock> lock = SessionLock::Acquire(request.session, request.options.wait);
  if (!lock.ok()) return lock.status();
  StatusOr<ReadingCheck> check = SessionReadingCheck(request.session);
  if (!check.ok()) return check.status();
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(request.session);
  if (!rows.ok()) return rows.status();

  AcquireResult result{request.session, controller.Describe(), camera.Describe(), {}, 0, 0, {}};
  result.settle_seconds = request.options.settle_seconds.value_or(controller.DefaultSettleSeconds());
  const int total = static_cast<int>(poses->size());
  std::vector<bool> skip(total);
  for (int index = 0; index < total; ++index) {
    PoseRecord& record = result.poses.emplace_back();
    record.index = index;
    record.pose = (*poses)[index];
    // Recorded when a row holds this pose (plan_captures.h), whatever its name.
    const int row = CaptureOfPose(*check, index, record.pose, *rows);
    skip[index] = row >= 0;
    record.state = skip[index] ? PoseState::kAlreadyRecorded : PoseState::kRecorded;
    record.image = skip[index] ? (*rows)[row].image : CaptureImageName(index, *rows);
  }
  result.visit_order = VisitOrder(*robot, *poses, WorkspaceCentre(*robot), skip);
  hooks.Stage("acquire");
  hooks.Progress(total - static_cast<int>(result.visit_order.size()), total);
  int done = total - static_cast<int>(result.visit_order.size());
  for (const int index : result.visit_order) {
    if (hooks.Cancelled()) return Status::Cancelled();
    StatusOr<PoseRecord> record = RunOnePose(request, result.poses[index], controller, camera, hooks);
    if (!record.ok()) return record.status();
    hooks.Note(PoseNote(*record, total));
    result.poses[index] = *record;
    hooks.Progress(++done, total);
  }
  result.seconds = SecondsSince(start);
  return result;
}

std::vector<int> VisitOrder(const Robot& robot, const std::vector<Vector6d>& poses, const Vector6d& start,
                            const std::vector<bool>& skip) {
  const auto scaled_legs = [&](const Vector6d& pose) {
    LegReadings legs = InverseKinematics(robot, robot.PoseFromVector(pose));
    for (int i = 0; i < kNumLegs; ++i) legs[i] /= robot.legs[i].stroke_max - robot.legs[i].stroke_min;
    return legs;
  };
  std::vector<LegReadings> legs;
  std::vector<int> left;
  for (size_t k = 0; k < poses.size(); ++k) {
    legs.push_back(scaled_legs(poses[k]));
    if (k >= skip.size() || !skip[k]) left.push_back(static_cast<int>(k));
  }
  std::vector<int> order;
  LegReadings here = scaled_legs(start);
  while (!left.empty()) {
    // The first of equally near poses, so that the order is the plan's for a tie.
    auto nearest = std::min_element(left.begin(), left.end(),
                                    [&](int a, int b) { return (legs[a] - here).norm() < (legs[b] - here).norm(); });
    order.push_back(*nearest);
    here = legs[*nearest];
    left.erase(nearest);
  }
  return order;
}

nlohmann::json ToJson(const AcquireResult& result) {
  nlohmann::json poses = nlohmann::json::array();
  for (const PoseRecord& r : result.poses) {
    nlohmann::json row = {{"index", r.index},
                          {"state", PoseStateName(r.state)},
                          {"image", r.image},
                          {"pose", std::vector<double>(r.pose.data(), r.pose.data() + 6)}};
    if (r.state == PoseState::kRecorded) {
      row["readings"] = std::vector<double>(r.readings.data(), r.readings.data() + kNumLegs);
      row["holdout"] = r.holdout;
      row["seconds"] = r.seconds;
    }
    if (r.state == PoseState::kFailed) row["error"] = r.error;
    poses.push_back(row);
  }
  return {{"session", result.session},
          {"controller", result.controller},
          {"camera", result.camera},
          {"recorded", result.Count(PoseState::kRecorded)},
          {"already_recorded", result.Count(PoseState::kAlreadyRecorded)},
          {"failed", result.Count(PoseState::kFailed)},
          {"poses", poses},
          {"visit_order", result.visit_order},
          {"settle_seconds", result.settle_seconds},
          {"seconds", result.seconds}};
}

std::string FormatAcquireSummary(const AcquireResult& result) {
  std::ostringstream text;
  text << "acquired into " << result.session << " with " << result.controller << " and " << result.camera << "\n"
       << "  " << result.Count(PoseState::kRecorded) << " recorded, " << result.Count(PoseState::kAlreadyRecorded)
       << " already recorded, " << result.Count(PoseState::kFailed) << " failed, of " << result.poses.size()
       << " poses in " << FormatNumber(std::round(result.seconds * 10) / 10) << " s (settle "
       << FormatNumber(result.settle_seconds) << " s after each move)\n";
  for (const PoseRecord& r : result.poses)
    if (r.state == PoseState::kFailed) text << "  failed: " << r.image << ": " << r.error << "\n";
  if (result.Count(PoseState::kFailed) > 0) text << "  run hexcal acquire again to retry the failed poses\n";
  return text.str();
}

}  // namespace hexcal::workflow

#include "workflow/verify_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "vision/board_pose.h"
#include "vision/image_codecs.h"
#include "vision/measure.h"
#include "workflow/acquire_step.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

// What the check needs from the session: robot (pose convention and unit),
// camera, target and the registered frames.
struct CheckInputs {
  Robot robot;
  Camera camera;
  Target target;
  Registration frames;
};

StatusOr<CheckInputs> LoadCheckInputs(const std::string& dir) {
  StatusOr<SessionModels> models = LoadSessionModels(dir);
  if (!models.ok()) return models.status();
  const SessionConfig& config = models->config;
  if (!config.base_from_camera || !config.platform_from_target)
    return Status::BadInput(dir +
                            ": the session has no registered camera and target frames; calibrate it first "
                            "(hexcal calibrate --session " +
                            dir + ")");
  Registration frames;
  frames.base_from_camera = *config.base_from_camera;
  frames.platform_from_target = *config.platform_from_target;
  return CheckInputs{std::move(models->robot), std::move(models->camera), std::move(models->target), frames};
}

cv::Mat Gray(const cv::Mat& frame) {
  if (frame.channels() == 1) return frame;
  cv::Mat gray;
  cv::cvtColor(frame, gray, frame.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

// Where the camera sees the platform, compared with the commanded pose.
void CompareWithCommanded(const CheckInputs& in, const BoardPose& board, PoseCheck* check) {
  Pose camera_from_target = board.camera_from_target;  // target unit
  camera_from_target.position *= MetresPerUnit(in.target.length_unit) / MetresPerUnit(in.robot.length_unit);
  const Pose seen = BaseFromPlatform(in.frames, camera_from_target);
  const Pose commanded = in.robot.PoseFromVector(check->commanded);
  check->seen = in.robot.VectorFromPose(seen);
  check->position_error = (seen.position - commanded.position).norm();
  check->orientation_error = RotationLog(commanded.rotation.transpose() * seen.rotation).norm() * 180 / M_PI;
  check->reprojection_rms_px = board.rms_px;
}

std::string FrameName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "check_%04d.png", index);
  return name;
}

Status KeepFrame(const std::string& folder, int index, const cv::Mat& frame) {
  StatusOr<std::string> png = EncodePng(frame);
  if (!png.ok()) return png.status();
  return WriteFileAtomically((std::filesystem::path(folder) / FrameName(index)).string(), *png);
}

// --keep-images, checked before anything moves: never the session's images/
// (or a folder in it: those are the recorded captures), and no frame file
// replaced without --force; then the folder is made.
Status CheckImagesOut(const VerifyRequest& request, size_t count) {
  namespace fs = std::filesystem;
  if (request.images_out.empty()) return Status::Ok();
  std::error_code error;
  const fs::path images = fs::weakly_canonical(SessionPaths(request.session).images, error);
  const fs::path out = fs::weakly_canonical(request.images_out, error);
  const auto [end, rest] = std::mismatch(images.begin(), images.end(), out.begin(), out.end());
  if (!error && end == images.end())
    return Status::BadInput("--keep-images " + request.images_out + ": that is the session's images/ folder, " +
                            "which holds the recorded captures: keep the frames in another folder");
  for (size_t k = 0; k < count && !request.force; ++k) {
    const fs::path frame = fs::path(request.images_out) / FrameName(static_cast<int>(k));
    if (fs::exists(fs::symlink_status(frame, error)))
      return Status::BadInput("--keep-images: " + frame.string() +
                              " exists: use another folder, or --force to replace");
  }
  return CreateFolders(request.images_out);
}

// One pose: move, settle, grab, measure, compare. Device errors are the pose's.
PoseCheck CheckOnePose(const VerifyRequest& request, const CheckInputs& in, AcquisitionRig& rig, TagDetector& detector,
                       int index, const Vector6d& pose) {
  PoseCheck check;
  check.index = index;
  check.commanded = pose;
  Status moved = rig.controller->MoveTo(pose);
  if (moved.ok()) moved = rig.controller->WaitSettled(request.settle_seconds);
  StatusOr<cv::Mat> frame =
      moved.ok() ? rig.camera->Grab(std::chrono::milliseconds(request.grab_timeout_ms)) : StatusOr<cv::Mat>(moved);
  if (!frame.ok()) {
    check.problem = frame.status().message();
    return check;
  }
  if (!request.images_out.empty())
    if (Status s = KeepFrame(request.images_out, index, *frame); !s.ok())
      check.problem = "the frame was not kept: " + s.message();
  const ImageMeasurement measured = MeasureImage(detector, Gray(*frame), in.camera, in.target, BoardPoseOptions{});
  if (measured.pose.status != PoseStatus::kOk) {
    check.problem = std::string("the board was not measured: ") + PoseStatusName(measured.pose.status) + " " +
                    measured.pose.message;
    return check;
  }
  CompareWithCommanded(in, measured.pose, &check);
  return check;
}

// Three significant digits, as the other summaries print figures.
std::string Figure(double value) {
  std::ostringstream out;
  out << std::setprecision(3) << value;
  return out.str();
}

void Summarise(VerifyResult* result) {
  double position_sum = 0, orientation_sum = 0;
  for (const PoseCheck& check : result->poses) {
    if (!check.seen) continue;
    position_sum += check.position_error * check.position_error;
    orientation_sum += check.orientation_error * check.orientation_error;
    result->position_max = std::max(result->position_max, check.position_error);
    result->orientation_max = std::max(result->orientation_max, check.orientation_error);
  }
  const int seen = result->Seen();
  if (seen == 0) return;
  result->position_rms = std::sqrt(position_sum / seen);
  result->orientation_rms = std::sqrt(orientation_sum / seen);
}

}  // namespace

int VerifyResult::Seen() const {
  int seen = 0;
  for (const PoseCheck& check : poses) seen += check.seen ? 1 : 0;
  return seen;
}

StatusOr<VerifyResult> VerifyPoses(const VerifyRequest& request, const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  AcquireOptions device;  // the Acquire step's rules for the same two numbers
  device.settle_seconds = request.settle_seconds;
  device.grab_timeout_ms = request.grab_timeout_ms;
  if (Status s = device.Check(); !s.ok()) return s;
  StatusOr<CheckInputs> in = LoadCheckInputs(request.session);
  if (!in.ok()) return in.status();
  StatusOr<std::vector<Vector6d>> poses =
      LoadPoses(request.poses.empty() ? SessionPaths(request.session).plan : request.poses);
  if (!poses.ok()) return poses.status();
  if (Status s = CheckImagesOut(request, poses->size()); !s.ok()) return s;
  StatusOr<std::unique_ptr<TagDetector>> detector =
      TagDetector::Create(ForTarget(DetectorOptions{}, in->target), std::make_shared<const IdealPixelMap>(in->camera));
  if (!detector.ok()) return detector.status();
  StatusOr<AcquisitionRig> rig =
      OpenAcquisitionRig(request.session, request.controller, request.camera, request.seed, TruthRecord::kCheckOnly);
  if (!rig.ok()) return rig.status();
  VerifyResult result;
  result.session = request.session;
  result.controller = rig->controller->Describe();
  result.camera = rig->camera->Describe();
  result.length_unit = LengthUnitName(in->robot.length_unit);
  hooks.Stage("verify");
  for (size_t k = 0; k < poses->size(); ++k) {
    if (hooks.Cancelled()) return Status::Cancelled();
    result.poses.push_back(CheckOnePose(request, *in, *rig, **detector, static_cast<int>(k), (*poses)[k]));
    const PoseCheck& check = result.poses.back();
    hooks.Note("pose " + std::to_string(k + 1) + "/" + std::to_string(poses->size()) + ": " +
               (check.seen ? "position error " + Figure(check.position_error) + " " + result.length_unit +
                                 ", orientation error " + Figure(check.orientation_error) + " deg"
                           : check.problem));
    hooks.Progress(static_cast<int>(k + 1), static_cast<int>(poses->size()));
  }
  Summarise(&result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

nlohmann::json ToJson(const VerifyResult& result) {
  nlohmann::json poses = nlohmann::json::array();
  for (const PoseCheck& check : result.poses) {
    nlohmann::json pose = {{"index", check.index},
                           {"commanded", std::vector<double>(check.commanded.data(), check.commanded.data() + 6)}};
    if (check.seen) {
      pose["seen"] = std::vector<double>(check.seen->data(), check.seen->data() + 6);
      pose["position_error"] = check.position_error;
      pose["orientation_error"] = check.orientation_error;
      pose["reprojection_rms_px"] = check.reprojection_rms_px;
    }
    if (!check.problem.empty()) pose["problem"] = check.problem;  // no pose seen, or its frame not kept
    poses.push_back(pose);
  }
  return {{"session", result.session},
          {"controller", result.controller},
          {"camera", result.camera},
          {"length_unit", result.length_unit},
          {"seen", result.Seen()},
          {"failed", static_cast<int>(result.poses.size()) - result.Seen()},
          {"position_rms", result.position_rms},
          {"position_max", result.position_max},
          {"orientation_rms", result.orientation_rms},
          {"orientation_max", result.orientation_max},
          {"seconds", result.seconds},
          {"poses", poses}};
}

std::string FormatVerifySummary(const VerifyResult& result) {
  std::ostringstream out;
  out << "checked " << result.poses.size() << " poses through the camera (" << result.Seen() << " seen, "
      << result.poses.size() - result.Seen() << " failed) in " << FormatNumber(std::round(result.seconds * 10) / 10)
      << " s\n  controller: " << result.controller << "\n  camera: " << result.camera << "\n";
  if (result.Seen() > 0)
    out << "commanded against seen: position RMS " << Figure(result.position_rms) << " " << result.length_unit
        << " (max " << Figure(result.position_max) << "), orientation RMS " << Figure(result.orientation_rms)
        << " deg (max " << Figure(result.orientation_max) << ")\n";
  return out.str();
}

}  // namespace hexcal::workflow

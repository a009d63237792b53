#include "sim/sim_world.h"

#include <chrono>
#include <cmath>
#include <thread>

#include "core/constraints.h"
#include "core/csv.h"
#include "core/forward_kinematics.h"
#include "core/registration.h"
#include "core/session.h"
#include "devices/controller.h"
#include "session/session_models.h"
#include "vision/renderer.h"

namespace hexcal::workflow {
namespace {

// The sim machine moves at once; settling is waited for as asked, so that a
// run's timing is that of the real machine's settle time.
class SimController final : public Controller {
 public:
  explicit SimController(std::shared_ptr<SimWorld> world) : world_(std::move(world)) {}

  Status MoveTo(const Vector6d& pose) override { return world_->Command(pose); }
  Status WaitSettled(double settle_seconds) override {
    if (settle_seconds > 0) std::this_thread::sleep_for(std::chrono::duration<double>(settle_seconds));
    return Status::Ok();
  }
  StatusOr<LegReadings> ReadLegs() override { return world_->ReadLegs(); }
  // The sim camera renders the pose the sim world holds: no latency to wait for.
  double DefaultSettleSeconds() const override { return 0; }
  std::string Describe() const override {
    return "sim controller (" + world_->scene().nominal.name + ", hidden true robot of seed " +
           std::to_string(world_->scene().seed) + ")";
  }

 private:
  std::shared_ptr<SimWorld> world_;
};

class SimFrameSource final : public FrameSource {
 public:
  explicit SimFrameSource(std::shared_ptr<SimWorld> world) : world_(std::move(world)) {}
  StatusOr<cv::Mat> Grab(std::chrono::milliseconds) override { return world_->RenderFrame(); }
  std::string Describe() const override {
    const Camera& camera = world_->scene().camera;
    return "sim camera (" + std::to_string(camera.width) + "x" + std::to_string(camera.height) + ", rendered)";
  }

 private:
  std::shared_ptr<SimWorld> world_;
};

}  // namespace

std::unique_ptr<Controller> MakeSimController(std::shared_ptr<SimWorld> world) {
  return std::make_unique<SimController>(std::move(world));
}

std::unique_ptr<FrameSource> MakeSimFrameSource(std::shared_ptr<SimWorld> world) {
  return std::make_unique<SimFrameSource>(std::move(world));
}

namespace {

// A points session names no camera or target: its world is the one `hexcal
// demo --instrument points` draws, with the sim camera's place for the
// tracker and the default board's for the reflectors, so that a demo
// session's truth is the sim world's of the same seed.
StatusOr<SessionModels> SimWorldModels(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  if (config->instrument != Instrument::kPoints) return LoadSessionModels(dir);
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  if (!robot.ok()) return robot.status();
  StatusOr<Camera> camera = LoadCamera(kSimulatedCameraName);
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(kDefaultTargetName);
  if (!target.ok()) return target.status();
  return SessionModels{std::move(*config), std::move(*robot), std::move(*camera), std::move(*target)};
}

}  // namespace

ControllerOptions SimControllerOptions(std::shared_ptr<SimWorld> world) {
  ControllerOptions options;
  if (world) options.sim = [world] { return MakeSimController(world); };
  return options;
}

FrameSourceOptions SimFrameSourceOptions(std::shared_ptr<SimWorld> world) {
  FrameSourceOptions options;
  if (world) options.sim = [world] { return MakeSimFrameSource(world); };
  return options;
}

StatusOr<std::shared_ptr<SimWorld>> SimWorld::ForSession(const std::string& dir, uint64_t seed) {
  StatusOr<SessionModels> models = SimWorldModels(dir);
  if (!models.ok()) return models.status();
  DemoSceneOptions options;
  options.seed = seed;
  auto world = std::make_shared<SimWorld>(MakeDemoScene(models->robot, models->camera, models->target, options));
  if (Status s = world->Command(WorkspaceCentre(models->robot)); !s.ok())
    return Status::BadInput(dir +
                            ": the sim machine cannot start at the centre of the robot's sampling box: " + s.message());
  return world;
}

SimWorld::SimWorld(DemoScene scene) : scene_(std::move(scene)), reading_noise_(scene_.seed * 7919 + 17) {
  RenderOptions render;
  render.seed = scene_.seed;
  renderer_ = std::make_unique<Renderer>(scene_.camera, scene_.target, render);
}

SimWorld::~SimWorld() = default;

Status SimWorld::Command(const Vector6d& pose_vector) {
  const Robot& nominal = scene_.nominal;
  if (Status s = CheckPoseInWorkspace(nominal, pose_vector); !s.ok()) return s;
  const Pose commanded = nominal.PoseFromVector(pose_vector);
  if (Status s = DriveLegs(InverseKinematics(nominal, commanded), commanded); !s.ok())
    return Status::Failed("pose " + PoseText(pose_vector) + ": " + s.message());
  return Status::Ok();
}

Status SimWorld::DriveLegs(const LegReadings& encoders, const std::optional<Pose>& near) {
  StatusOr<LocalFkResult> actual = ForwardKinematicsLocal(scene_.truth, encoders, near ? *near : ActualPose());
  if (!actual.ok())
    return Status::Failed("the simulated platform has no pose for the legs " + PoseText(encoders) + ": " +
                          actual.status().message());
  std::lock_guard<std::mutex> hold(mutex_);
  driven_legs_ = encoders;
  actual_pose_ = actual->pose;
  return Status::Ok();
}

LegReadings SimWorld::ReadLegs() {
  std::lock_guard<std::mutex> hold(mutex_);
  std::uniform_real_distribution<double> unit_noise(-1, 1);
  LegReadings readings = driven_legs_;
  for (int i = 0; i < kNumLegs; ++i) readings[i] += scene_.noise.leg * unit_noise(reading_noise_);
  return readings;
}

cv::Mat SimWorld::RenderFrame() {
  Pose base_from_platform;
  uint64_t index = 0;
  {
    std::lock_guard<std::mutex> hold(mutex_);
    base_from_platform = actual_pose_;
    index = frames_rendered_++;
  }
  // camera_from_target = X⁻¹ · base_from_platform · Y, in the target's unit (as RecordDemoSession).
  Pose camera_from_target = CameraFromTarget(scene_.base_from_camera, base_from_platform, scene_.platform_from_target);
  camera_from_target.position *= MetresPerUnit(scene_.nominal.length_unit) / MetresPerUnit(scene_.target.length_unit);
  return renderer_->Render(camera_from_target, index).image;
}

Pose SimWorld::ActualPose() const {
  std::lock_guard<std::mutex> hold(mutex_);
  return actual_pose_;
}

Status SimWorld::WriteTruth(const std::string& session_dir) const { return WriteSceneTruth(scene_, session_dir); }

}  // namespace hexcal::workflow

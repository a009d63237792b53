#include "workflow/sim_world.h"

#include <cmath>

#include "core/constraints.h"
#include "core/csv.h"
#include "core/forward_kinematics.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "vision/renderer.h"
#include "workflow/controller.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

}  // namespace

StatusOr<std::shared_ptr<SimWorld>> SimWorld::ForSession(const std::string& dir, uint64_t seed) {
  StatusOr<SessionModels> models = LoadSessionModels(dir);
  if (!models.ok()) return models.status();
  DemoSceneOptions options;
  options.seed = seed;
  auto world = std::make_shared<SimWorld>(MakeDemoScene(models->robot, models->camera, models->target, options));
  if (Status s = world->Command(WorkspaceCentre(models->robot)); !s.ok())
    return Status::Error(dir +
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
  Pose camera_from_target =
      Compose(Compose(Inverse(scene_.base_from_camera), base_from_platform), scene_.platform_from_target);
  camera_from_target.position *= MetresPerUnit(scene_.nominal.length_unit) / MetresPerUnit(scene_.target.length_unit);
  return renderer_->Render(camera_from_target, index).image;
}

Pose SimWorld::ActualPose() const {
  std::lock_guard<std::mutex> hold(mutex_);
  return actual_pose_;
}

Status SimWorld::WriteTruth(const std::string& session_dir) const { return WriteSceneTruth(scene_, session_dir); }

}  // namespace hexcal::workflow

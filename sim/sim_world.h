// The simulated laboratory behind the `sim` controller and the `sim` camera
// (docs/acquisition.md, "The sim world"): one hidden true robot, camera and
// target made as `hexcal demo` makes them (sim/demo_scene.h) from the
// session's nominal robot, camera and target, and the state of the machine.
//
// A commanded pose goes through the controller's model, the nominal robot:
// its IK gives the leg lengths the actuators are driven to. The platform then
// sits where the TRUE robot puts those legs (its local FK from the commanded
// pose); the sensors read the legs with uniform noise of ±noise.leg; the
// camera sees the board at that true pose, rendered with the demo's renderer
// and sensor noise. So the difference between nominal and true robot is what
// a calibration from the recorded images and readings has to find.
//
//   StatusOr<std::shared_ptr<SimWorld>> world = SimWorld::ForSession("run1", /*seed=*/1);
//   Status moved = (*world)->Command(pose);        // robot unit, degrees
//   LegReadings legs = (*world)->ReadLegs();
//   cv::Mat image = (*world)->RenderFrame();
//
// Thread-safe: the controller and the camera may be driven from two threads.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <random>
#include <string>

#include "core/inverse_kinematics.h"
#include "core/pose.h"
#include "core/status.h"
#include "devices/controller.h"
#include "devices/frame_source.h"
#include "sim/demo_scene.h"

namespace hexcal {
class Renderer;
}

namespace hexcal::workflow {

class SimWorld {
 public:
  // The world of a session: its robot, camera and target as session.yaml
  // names them, the truth drawn from `seed` (DemoSceneOptions). The platform
  // starts at the centre of the robot's sampling box.
  static StatusOr<std::shared_ptr<SimWorld>> ForSession(const std::string& session_dir, uint64_t seed);

  explicit SimWorld(DemoScene scene);
  ~SimWorld();
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  // Drives the legs to the nominal IK of `pose` (x, y, z in the robot unit,
  // q1..q3 in degrees, the robot's Euler convention): bad input when the
  // nominal robot cannot reach it (its workspace constraints), a failure when
  // the true robot has no pose for those legs near it. The machine stays where
  // it was on an error.
  Status Command(const Vector6d& pose);
  // Drives the legs to `encoders` (the readings the sensors would show
  // without noise), as a machine that is not the sim controller does: the
  // platform sits where the true robot puts those legs, found by local FK
  // from where it is now. A failure (the machine stays) when the true robot
  // has no pose near it for them. The `sim-camera` command follows a
  // LinuxCNC machine's joints this way (sim/machine_follower.h), with
  // `near` the machine's own idea of the pose (its model's FK), a start the
  // FK converges from however far the platform moved since the last call.
  Status DriveLegs(const LegReadings& encoders, const std::optional<Pose>& near = std::nullopt);
  // The leg sensors: the driven lengths plus uniform noise of ±noise.leg.
  LegReadings ReadLegs();
  // The camera's image of the board at the true platform pose (CV_8UC1).
  cv::Mat RenderFrame();
  // Where the platform really is (the true robot's frames).
  Pose ActualPose() const;

  const DemoScene& scene() const { return scene_; }
  // Writes the truth to DIR/truth/ (WriteSceneTruth).
  Status WriteTruth(const std::string& session_dir) const;

 private:
  mutable std::mutex mutex_;
  const DemoScene scene_;
  std::unique_ptr<Renderer> renderer_;
  LegReadings driven_legs_ = LegReadings::Zero();
  Pose actual_pose_;
  std::mt19937_64 reading_noise_;
  uint64_t frames_rendered_ = 0;
};

// The `sim` controller, which moves `world` at once (settling is waited for as
// asked), and the `sim` camera, which renders what `world` shows.
std::unique_ptr<Controller> MakeSimController(std::shared_ptr<SimWorld> world);
std::unique_ptr<FrameSource> MakeSimFrameSource(std::shared_ptr<SimWorld> world);
// The options that let OpenController and OpenFrameSource (devices/device_urls.h)
// open the `sim` URL on `world`; for a null world, options without it (the
// URL is then refused as needing the sim world).
ControllerOptions SimControllerOptions(std::shared_ptr<SimWorld> world);
FrameSourceOptions SimFrameSourceOptions(std::shared_ptr<SimWorld> world);

}  // namespace hexcal::workflow

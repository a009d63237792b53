// The sim world following a LinuxCNC machine, for `hexcal sim-camera`
// (docs/acquisition.md, "The closed loop in simulation"): LinuxCNC's
// simulated drives move joints, not a platform; this follower turns the
// joints into where the hidden TRUE robot's platform would be, so that a
// camera of the sim world (workflow/sim_world.h) shows what a real camera
// would see of the real machine.
//
// It keeps its own linuxcncrsh connection and only reads (`hello`,
// `get user_linear_units`, `get joint_pos`; never `set enable`), so it runs
// beside the controller of `hexcal acquire`. Each poll's joints become the
// legs' encoder readings through the robot file the machine runs with
// (L = joint / scale − l, workflow/linuxcnc_geometry.h: that file's offsets l
// are the machine's joint homes), the world's legs are driven there
// (SimWorld::DriveLegs) and, when they moved, the world's frame is rendered
// again. A lost connection (the machine restarted, with another robot file
// perhaps) is retried, and the robot file read again, until the follower
// stops.
//
//   auto follower = MachineFollower::Start(address, "machine/robot.yaml", world, {});
//   cv::Mat frame = (*follower)->LatestFrame();  // the platform where the joints put it
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "core/status.h"
#include "workflow/linuxcnc_controller.h"
#include "workflow/sim_world.h"

namespace hexcal::workflow {

struct FollowerOptions {
  std::chrono::milliseconds poll_interval{40};  // one frame period of the fake camera (25 fps)
  std::chrono::milliseconds reply_timeout{2000};
  std::chrono::milliseconds retry_interval{250};  // after a lost connection
  // Joints that moved by less than this (machine units) leave the frame as it is.
  double joint_tolerance = 1e-7;
};

class MachineFollower {
 public:
  // Connects once (so that a wrong address is an error now, not a silent
  // retry loop), renders the first frame and starts polling.
  static StatusOr<std::unique_ptr<MachineFollower>> Start(const LinuxCncAddress& address,
                                                          const std::string& machine_robot_file,
                                                          std::shared_ptr<SimWorld> world,
                                                          const FollowerOptions& options);
  ~MachineFollower();  // stops polling
  MachineFollower(const MachineFollower&) = delete;
  MachineFollower& operator=(const MachineFollower&) = delete;

  // The world's image of the platform at the joints last read (CV_8UC1).
  cv::Mat LatestFrame() const;
  // Polls that changed the frame, and the latest problem ("" if none): for logs.
  uint64_t frames_rendered() const { return frames_rendered_; }
  std::string Problem() const;

  struct Connection;  // a linuxcncrsh session and the machine's robot file (machine_follower.cc)

 private:
  MachineFollower(LinuxCncAddress address, std::string robot_file, std::shared_ptr<SimWorld> world,
                  FollowerOptions options);
  // One poll: read the joints, drive the world, render if they moved. An
  // error is the connection's (a lost or unreadable reply).
  Status Poll(Connection& connection);
  void Run();
  void SetProblem(const std::string& problem);

  const LinuxCncAddress address_;
  const std::string robot_file_;
  const std::shared_ptr<SimWorld> world_;
  const FollowerOptions options_;
  std::unique_ptr<Connection> connection_;
  Vector6d last_joints_;
  bool have_joints_ = false;
  mutable std::mutex mutex_;  // guards frame_ and problem_
  cv::Mat frame_;
  std::string problem_;
  std::atomic<uint64_t> frames_rendered_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace hexcal::workflow

// The sim world following a LinuxCNC machine, for `hexcal sim-camera`
// (docs/acquisition.md, "The closed loop in simulation"): LinuxCNC's
// simulated drives move joints, not a platform; this follower turns the
// joints into where the hidden TRUE robot's platform would be, so that a
// camera of the sim world (sim/sim_world.h) shows what a real camera
// would see of the real machine.
//
// It reads the machine on this host through LinuxCNC's status channel (its
// Python module `linuxcnc`, in a child process of Debian's /usr/bin/python3:
// shared memory, read-only), not through linuxcncrsh, whose sessions share
// reply buffers: a second client there garbled the controller's replies
// (`ABS_ACT_POS 0 -49.03`). Each poll's joints become the legs' encoder
// readings through the robot file the machine runs with (L = joint / scale −
// l, devices/linuxcnc_geometry.h: that file's offsets l are the machine's
// joint homes); the true FK starts from the machine's own world pose (its
// model's FK), within the model's error of the truth; the world's frame is
// rendered again when the joints moved. Before homing the platform stays
// where it is. The robot file is read again when it changes (the machine was
// restarted with another robot), and a machine that is down is waited for.
//
//   auto follower = MachineFollower::Start("machine/robot.yaml", world, {});
//   cv::Mat frame = (*follower)->LatestFrame();  // the platform where the joints put it
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "core/status.h"
#include "devices/linuxcnc_geometry.h"
#include "sim/sim_world.h"

namespace hexcal::workflow {

struct FollowerOptions {
  std::string python = "/usr/bin/python3";  // with LinuxCNC's module `linuxcnc`
  MachineUnit unit = MachineUnit::kMillimetre;  // the machine's [TRAJ] LINEAR_UNITS
  std::chrono::milliseconds poll_interval{20};
  std::chrono::milliseconds reply_timeout{2000};
  // Joints that moved by less than this (machine units) leave the frame as it is.
  double joint_tolerance = 1e-7;
};

class MachineFollower {
 public:
  // Starts the status reader and renders the first frame (the platform where
  // the world starts, if the machine is down or not homed).
  static StatusOr<std::unique_ptr<MachineFollower>> Start(const std::string& machine_robot_file,
                                                          std::shared_ptr<SimWorld> world,
                                                          const FollowerOptions& options);
  ~MachineFollower();  // stops polling and the reader
  MachineFollower(const MachineFollower&) = delete;
  MachineFollower& operator=(const MachineFollower&) = delete;

  // The world's image of the platform at the joints last read (CV_8UC1).
  cv::Mat LatestFrame() const;
  // Polls that changed the frame, and the latest problem ("" if none): for logs.
  uint64_t frames_rendered() const { return frames_rendered_; }
  std::string Problem() const;

  struct Reader;  // the status reader process and its socket (machine_follower.cc)

 private:
  MachineFollower(std::string robot_file, std::shared_ptr<SimWorld> world, FollowerOptions options);
  // The machine's robot file, read again when it changed.
  Status RefreshRobot();
  // One status line: drive the world, render if the joints moved.
  Status Follow(const std::string& line);
  void Run();
  void SetProblem(const std::string& problem);
  void SetFrame(cv::Mat frame);

  const std::string robot_file_;
  const std::shared_ptr<SimWorld> world_;
  const FollowerOptions options_;
  std::unique_ptr<Reader> reader_;
  Robot robot_;
  std::filesystem::file_time_type robot_time_{};
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

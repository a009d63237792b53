#include "sim/machine_follower.h"

#include <signal.h>
#include <unistd.h>

#include <utility>

#include "core/atomic_file.h"
#include "core/robot_io.h"
#include "devices/child_process.h"
#include "devices/line_client.h"
#include "devices/linuxcnc_reply.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// The status reader: LinuxCNC's status channel every argv[1] seconds, as
// "STATUS homed j0..j5 X Y Z A B C", or "DOWN why" while no machine runs. A
// new stat() each time, so that a restarted machine's channel is the one read.
// X..C is the commanded world pose (`position`), not `actual_position`:
// that is genhexkins' FK of the joints, which fails at large rotations and
// then holds a stale pose (docs/acquisition.md).
constexpr const char* kStatusReader = R"(import sys, time
import linuxcnc
while True:
    try:
        s = linuxcnc.stat()
        s.poll()
        homed = all(j["homed"] for j in s.joint[:6])
        print("STATUS", int(homed), *s.joint_actual_position[:6], *s.position[:6], flush=True)
    except linuxcnc.error as e:
        print("DOWN", str(e).replace("\n", " "), flush=True)
    time.sleep(float(sys.argv[1]))
)";

// "STATUS homed j0..j5 X Y Z A B C": 14 words.
struct MachineStatus {
  bool homed = false;
  Vector6d joints, world;
};

StatusOr<MachineStatus> ParseStatus(const std::string& line) {
  const std::vector<std::string> words = ReplyWords(line);
  if (!words.empty() && words[0] == "DOWN") return Status::Failed("no LinuxCNC machine runs on this host: " + line);
  MachineStatus status;
  double values[13];
  bool numbers = words.size() == 14 && words[0] == "STATUS";
  for (int k = 0; numbers && k < 13; ++k) numbers = ParseFiniteNumber(words[k + 1], &values[k]);
  if (!numbers) return Status::Failed("the status reader printed " + Excerpt(line));
  status.homed = values[0] != 0;
  for (int k = 0; k < 6; ++k) {
    status.joints[k] = values[1 + k];
    status.world[k] = values[7 + k];
  }
  return status;
}

}  // namespace

struct MachineFollower::Reader {
  pid_t pid = -1;
  LineClient lines;
  ~Reader() {
    kill(pid, SIGTERM);
    WaitChild(pid);
  }
};

namespace {

StatusOr<std::unique_ptr<MachineFollower::Reader>> StartReader(const FollowerOptions& options) {
  const std::string interval = std::to_string(options.poll_interval.count() / 1000.0);
  StatusOr<ChildProcess> child = SpawnWithOutputSocket({options.python, "-c", kStatusReader, interval}, true);
  if (!child.ok()) return child.status();
  return std::unique_ptr<MachineFollower::Reader>(
      new MachineFollower::Reader{child->pid, LineClient::Adopt(child->fd, "LinuxCNC status reader")});
}

}  // namespace

MachineFollower::MachineFollower(std::string robot_file, std::shared_ptr<SimWorld> world, FollowerOptions options)
    : robot_file_(std::move(robot_file)),
      world_(std::move(world)),
      options_(std::move(options)),
      last_joints_(Vector6d::Zero()) {}

StatusOr<std::unique_ptr<MachineFollower>> MachineFollower::Start(const std::string& machine_robot_file,
                                                                  std::shared_ptr<SimWorld> world,
                                                                  const FollowerOptions& options) {
  std::unique_ptr<MachineFollower> follower(new MachineFollower(machine_robot_file, world, options));
  if (Status s = follower->RefreshRobot(); !s.ok()) return s;
  StatusOr<std::unique_ptr<Reader>> reader = StartReader(options);
  if (!reader.ok()) return reader.status();
  // The first line says whether the reader works at all (python, its module).
  StatusOr<std::string> first = (*reader)->lines.ReadLine(options.reply_timeout * 5);
  if (!first.ok())
    return Status::Failed("the LinuxCNC status reader (" + options.python +
                          " with LinuxCNC's module linuxcnc) printed nothing: " + first.status().message());
  follower->reader_ = std::move(*reader);
  if (Status s = follower->Follow(*first); !s.ok()) follower->SetProblem(s.message());
  if (follower->LatestFrame().empty()) follower->SetFrame(world->RenderFrame());
  follower->thread_ = std::thread([raw = follower.get()] { raw->Run(); });
  return follower;
}

MachineFollower::~MachineFollower() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

Status MachineFollower::RefreshRobot() {
  std::error_code error;
  const fs::file_time_type time = fs::last_write_time(robot_file_, error);
  if (error) return FileSystemError(robot_file_, "cannot read the machine's robot file", error.value());
  if (time == robot_time_ && !robot_.name.empty()) return Status::Ok();
  StatusOr<Robot> robot = LoadRobot(robot_file_);
  if (!robot.ok()) return robot.status();
  robot_ = std::move(*robot);
  robot_time_ = time;
  have_joints_ = false;  // another robot: the same joints are other legs
  return Status::Ok();
}

Status MachineFollower::Follow(const std::string& line) {
  StatusOr<MachineStatus> status = ParseStatus(line);
  if (!status.ok()) return status.status();
  // Before homing, joint positions are counts from power-on, not leg lengths.
  if (!status->homed) return Status::Failed("the machine is not homed: the platform stays where it is");
  if (Status s = RefreshRobot(); !s.ok()) return s;
  const bool moved = !have_joints_ || (status->joints - last_joints_).cwiseAbs().maxCoeff() > options_.joint_tolerance;
  if (!moved) return Status::Ok();
  // The machine's commanded world pose is within the model's error (and the
  // drives' following error) of the true pose: the true FK starts there.
  const Pose near = PoseFromGenhexkinsWorld(robot_, status->world, options_.unit);
  if (Status s = world_->DriveLegs(ReadingsFromJoints(robot_, status->joints, options_.unit), near); !s.ok()) return s;
  last_joints_ = status->joints;
  have_joints_ = true;
  SetFrame(world_->RenderFrame());
  ++frames_rendered_;
  SetProblem("");
  return Status::Ok();
}

void MachineFollower::Run() {
  while (!stop_) {
    if (!reader_) {
      std::this_thread::sleep_for(options_.reply_timeout / 4);
      StatusOr<std::unique_ptr<Reader>> reader = StartReader(options_);
      if (!reader.ok()) {
        SetProblem(reader.status().message());
        continue;
      }
      reader_ = std::move(*reader);
    }
    StatusOr<std::string> line = reader_->lines.ReadLine(options_.reply_timeout);
    if (!line.ok()) {  // the reader died or hangs: start another
      SetProblem("the LinuxCNC status reader: " + line.status().message());
      reader_.reset();
      continue;
    }
    // Lines that came while the last frame was rendered are old: the newest counts.
    for (StatusOr<std::string> newer = reader_->lines.ReadLine(std::chrono::milliseconds(0)); newer.ok();
         newer = reader_->lines.ReadLine(std::chrono::milliseconds(0)))
      line = std::move(newer);
    if (Status s = Follow(*line); !s.ok()) SetProblem(s.message());
  }
}

cv::Mat MachineFollower::LatestFrame() const {
  std::lock_guard<std::mutex> hold(mutex_);
  return frame_;
}

std::string MachineFollower::Problem() const {
  std::lock_guard<std::mutex> hold(mutex_);
  return problem_;
}

void MachineFollower::SetProblem(const std::string& problem) {
  std::lock_guard<std::mutex> hold(mutex_);
  problem_ = problem;
}

void MachineFollower::SetFrame(cv::Mat frame) {
  std::lock_guard<std::mutex> hold(mutex_);
  frame_ = std::move(frame);
}

}  // namespace hexcal::workflow

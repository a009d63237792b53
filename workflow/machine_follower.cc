#include "workflow/machine_follower.h"

#include <algorithm>
#include <utility>

#include "core/robot_io.h"
#include "workflow/line_client.h"
#include "workflow/linuxcnc_geometry.h"
#include "workflow/linuxcnc_reply.h"

namespace hexcal::workflow {

struct MachineFollower::Connection {
  LineClient client;
  Robot robot;  // the robot file the machine runs with: its offsets l
  MachineUnit unit = MachineUnit::kMillimetre;
};

namespace {

// Sends `command` and returns the first reply line whose first word is `key`.
// Up to two other lines are skipped: linuxcncrsh echoes commands until
// `set echo off` has been read.
StatusOr<std::string> AskFor(LineClient& client, const std::string& command, const std::string& key,
                             std::chrono::milliseconds timeout) {
  if (Status s = client.Send(command); !s.ok()) return s;
  for (int line = 0; line < 3; ++line) {
    StatusOr<std::string> reply = client.ReadLine(timeout);
    if (!reply.ok()) return Status::Failed("'" + command + "': " + reply.status().message());
    const std::vector<std::string> words = ReplyWords(*reply);
    if (!words.empty() && UpperCase(words[0]) == key) return reply;
  }
  return Status::Failed("'" + command + "' got no " + key + " reply");
}

StatusOr<MachineUnit> AskUnit(LineClient& client, std::chrono::milliseconds timeout) {
  StatusOr<std::string> reply = AskFor(client, "get user_linear_units", "USER_LINEAR_UNITS", timeout);
  if (!reply.ok()) return reply.status();
  const std::vector<std::string> words = ReplyWords(*reply);
  const std::optional<MachineUnit> unit = words.size() == 2 ? ParseMachineUnit(words[1]) : std::nullopt;
  if (!unit) return Status::Failed("the machine's linear unit is " + Excerpt(*reply) + ": expected mm or inch");
  return *unit;
}

StatusOr<std::unique_ptr<MachineFollower::Connection>> Connect(const LinuxCncAddress& address,
                                                              const std::string& robot_file,
                                                              std::chrono::milliseconds timeout) {
  StatusOr<Robot> robot = LoadRobot(robot_file);
  if (!robot.ok()) return robot.status();
  StatusOr<LineClient> client = LineClient::Connect(address.host, address.port, timeout);
  if (!client.ok()) return client.status();
  StatusOr<std::string> hello = AskFor(*client, "hello EMC hexcal-follower 1.0", "HELLO", timeout);
  if (!hello.ok()) return hello.status();
  if (ReplyWords(*hello).size() < 2 || UpperCase(ReplyWords(*hello)[1]) != "ACK")
    return Status::Failed("linuxcncrsh refused the connection: " + Excerpt(*hello));
  if (Status s = client->Send("set echo off"); !s.ok()) return s;
  StatusOr<MachineUnit> unit = AskUnit(*client, timeout);
  if (!unit.ok()) return unit.status();
  return std::make_unique<MachineFollower::Connection>(
      MachineFollower::Connection{std::move(*client), std::move(*robot), *unit});
}

}  // namespace

MachineFollower::MachineFollower(LinuxCncAddress address, std::string robot_file, std::shared_ptr<SimWorld> world,
                                 FollowerOptions options)
    : address_(std::move(address)),
      robot_file_(std::move(robot_file)),
      world_(std::move(world)),
      options_(options),
      last_joints_(Vector6d::Zero()) {}

StatusOr<std::unique_ptr<MachineFollower>> MachineFollower::Start(const LinuxCncAddress& address,
                                                                  const std::string& machine_robot_file,
                                                                  std::shared_ptr<SimWorld> world,
                                                                  const FollowerOptions& options) {
  std::unique_ptr<MachineFollower> follower(new MachineFollower(address, machine_robot_file, world, options));
  StatusOr<std::unique_ptr<Connection>> connection = Connect(address, machine_robot_file, options.reply_timeout);
  if (!connection.ok())
    return Status::Failed("following LinuxCNC at " + address.host + ":" + std::to_string(address.port) + ": " +
                          connection.status().message());
  follower->connection_ = std::move(*connection);
  if (Status s = follower->Poll(*follower->connection_); !s.ok()) return s;
  if (follower->LatestFrame().empty()) {  // not homed, or legs out of reach: the platform where it starts
    std::lock_guard<std::mutex> hold(follower->mutex_);
    follower->frame_ = follower->world_->RenderFrame();
  }
  follower->thread_ = std::thread([raw = follower.get()] { raw->Run(); });
  return follower;
}

MachineFollower::~MachineFollower() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

Status MachineFollower::Poll(Connection& connection) {
  // Before homing, joint positions are counts from power-on, not leg lengths.
  StatusOr<std::string> homed = AskFor(connection.client, "get joint_homed", "JOINT_HOMED", options_.reply_timeout);
  if (!homed.ok()) return homed.status();
  const std::vector<std::string> flags = ReplyWords(*homed);
  if (flags.size() != 7 || std::any_of(flags.begin() + 1, flags.end(), [](const std::string& flag) {
        return UpperCase(flag) != "YES";
      })) {
    SetProblem("the machine is not homed: the platform stays where it is");
    return Status::Ok();
  }
  StatusOr<std::string> reply = AskFor(connection.client, "get joint_pos", "JOINT_POS", options_.reply_timeout);
  if (!reply.ok()) return reply.status();
  const std::optional<Vector6d> joints = SixNumbersAfter("JOINT_POS", *reply);
  if (!joints) return Status::Failed("'get joint_pos' was answered " + Excerpt(*reply));
  const bool moved = !have_joints_ || (*joints - last_joints_).cwiseAbs().maxCoeff() > options_.joint_tolerance;
  if (!moved) return Status::Ok();
  // Legs the true robot cannot take leave the platform where it was; the
  // connection is fine, so this is a problem to report, not to reconnect for.
  if (Status s = world_->DriveLegs(ReadingsFromJoints(connection.robot, *joints, connection.unit)); !s.ok()) {
    SetProblem(s.message());
    return Status::Ok();
  }
  last_joints_ = *joints;
  have_joints_ = true;
  cv::Mat frame = world_->RenderFrame();
  ++frames_rendered_;
  std::lock_guard<std::mutex> hold(mutex_);
  frame_ = std::move(frame);
  problem_.clear();
  return Status::Ok();
}

void MachineFollower::Run() {
  while (!stop_) {
    if (!connection_) {
      StatusOr<std::unique_ptr<Connection>> connection = Connect(address_, robot_file_, options_.reply_timeout);
      if (!connection.ok()) {
        SetProblem("reconnecting: " + connection.status().message());
        std::this_thread::sleep_for(options_.retry_interval);
        continue;
      }
      connection_ = std::move(*connection);
      have_joints_ = false;  // a restarted machine: render its pose whatever it is
      SetProblem("");
    }
    // A lost or garbled reply leaves the connection out of step: start again.
    if (Status s = Poll(*connection_); !s.ok()) {
      SetProblem(s.message());
      connection_.reset();
    }
    std::this_thread::sleep_for(options_.poll_interval);
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

}  // namespace hexcal::workflow

#include "devices/linuxcnc_controller.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "core/straight_moves.h"
#include "devices/line_client.h"
#include "devices/linuxcnc_geometry.h"
#include "devices/linuxcnc_reply.h"

namespace hexcal::workflow {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The six-number form of a pose in messages: "(x, y, z, a, b, c)".
std::string SixText(const Vector6d& values) {
  std::string text = "(";
  for (int k = 0; k < 6; ++k) text += FixedNumber(values[k], 6) + (k < 5 ? ", " : ")");
  return text;
}

class LinuxCncController final : public Controller {
 public:
  LinuxCncController(LineClient client, Robot robot, LinuxCncOptions options)
      : client_(std::move(client)), robot_(std::move(robot)), options_(std::move(options)) {}
  ~LinuxCncController() override { (void)client_.Send("quit"); }

  // The opening sequence of linuxcnc_controller.h.
  Status Open();
  Status MoveTo(const Vector6d& pose) override;
  // Sends one G0 from `from` to `world` (machine units, degrees); `text` names it in messages.
  Status SendMove(const Vector6d& from, const Vector6d& world, const std::string& text);
  Status WaitSettled(double settle_seconds) override;
  StatusOr<LegReadings> ReadLegs() override;
  // A machine reports "in position" before its structure stops ringing, and
  // a camera's frame lags (hexcal sim-camera renders after the status
  // update): with 0, frames showed the previous pose (docs/acquisition.md).
  double DefaultSettleSeconds() const override { return 0.5; }
  bool Usable() const override { return !stuck_; }
  // Homes every joint, homed or not, until the joints are at `joints`
  // (machine units) within `tolerance`, and returns to MDI mode (RehomeLinuxCnc).
  Status Rehome(const Vector6d& joints, double tolerance);
  std::string Describe() const override {
    return "LinuxCNC at " + client_.peer() + " (" + server_ + ", machine in " + MachineUnitName(unit_) + ", robot " +
           robot_.name + " in " + LengthUnitName(robot_.length_unit) + ")";
  }

 private:
  Status Error(const std::string& problem) const {
    return Status::Failed("LinuxCNC at " + client_.peer() + ": " + problem);
  }
  Status Unexpected(const std::string& command, const std::string& reply, const std::string& expected) const {
    return Error("'" + command + "' was answered " + Excerpt(reply) + " (expected " + expected + ")");
  }
  StatusOr<std::string> Ask(const std::string& command);
  Status Expect(const std::string& command, const std::string& acknowledgement, const std::string& hint = "");
  // The reply "KEY word ..." to `command`, as its words after KEY.
  StatusOr<std::vector<std::string>> AskWords(const std::string& command, const std::string& key, size_t count);
  StatusOr<Vector6d> AskSixNumbers(const std::string& command, const std::string& key);
  Status Handshake();
  Status CheckUnits();
  Status HomeIfNeeded();
  StatusOr<bool> AllHomed();
  // Polls AllHomed until every joint is homed, within `seconds`.
  Status WaitHomed(double seconds);
  // The oldest error message the machine has not reported yet; empty if none.
  StatusOr<std::string> NextMachineError();
  Status DiscardOldErrors();
  struct Motion {
    bool idle = false;         // the program (the MDI command) has ended
    bool in_position = false;  // and the platform is at the commanded pose
  };
  StatusOr<Motion> PollMotion();
  // Stops the motion (`set abort`: the planner's queue is dropped and the
  // machine decelerates) and returns `why` with what the abort answered.
  Status AbortMotion(Status why);
  // The settle time, in poll-interval slices so that a cancel ends it.
  Status Settle(double seconds);

  LineClient client_;
  Robot robot_;
  LinuxCncOptions options_;
  MachineUnit unit_ = MachineUnit::kMillimetre;
  std::string server_ = "linuxcncrsh";      // the HELLO ACK's server name and version
  Vector6d target_ = Vector6d::Zero();      // the commanded world pose, machine units and degrees
  Vector6d move_start_ = Vector6d::Zero();  // where the move to target_ started, the same units
  std::string target_text_;                 // hexcal's pose, for messages
  std::string lost_;                        // why the connection was given up, if it was
  bool moving_ = false;                     // a MoveTo was accepted and WaitSettled has not confirmed it
  bool stuck_ = false;                      // a move timed out or stopped away from its target
  std::optional<Vector6d> last_joints_;     // the joints at the last poll of an idle machine, machine units
};

StatusOr<std::string> LinuxCncController::Ask(const std::string& command) {
  // After a lost or late reply, the next line read could be the answer to an
  // earlier command: the connection is not used again.
  if (!lost_.empty()) return Error("the connection is unusable since an earlier error (" + lost_ + "); reconnect");
  Status sent = client_.Send(command);
  StatusOr<std::string> reply = sent.ok() ? client_.ReadLine(options_.reply_timeout) : StatusOr<std::string>(sent);
  if (reply.ok()) return reply;
  lost_ = "'" + command + "': " + reply.status().message();
  return Error(lost_);
}

Status LinuxCncController::Expect(const std::string& command, const std::string& acknowledgement,
                                  const std::string& hint) {
  StatusOr<std::string> reply = Ask(command);
  if (!reply.ok()) return reply.status();
  if (UpperCase(JoinWords(ReplyWords(*reply))) == acknowledgement) return Status::Ok();
  Status unexpected = Unexpected(command, *reply, "'" + acknowledgement + "'");
  return hint.empty() ? unexpected : Status::Failed(unexpected.message() + ": " + hint);
}

StatusOr<std::vector<std::string>> LinuxCncController::AskWords(const std::string& command, const std::string& key,
                                                                size_t count) {
  StatusOr<std::string> reply = Ask(command);
  if (!reply.ok()) return reply.status();
  std::vector<std::string> words = ReplyWords(*reply);
  if (words.size() != count + 1 || UpperCase(words[0]) != key)
    return Unexpected(command, *reply, key + " and " + std::to_string(count) + " value(s)");
  words.erase(words.begin());
  return words;
}

StatusOr<Vector6d> LinuxCncController::AskSixNumbers(const std::string& command, const std::string& key) {
  StatusOr<std::vector<std::string>> words = AskWords(command, key, 6);
  if (!words.ok()) return words.status();
  Vector6d values;
  for (int k = 0; k < 6; ++k)
    if (!ParseFiniteNumber((*words)[k], &values[k]))
      return Error("'" + command + "': value " + std::to_string(k + 1) + " is not a number: " + Excerpt((*words)[k]));
  return values;
}

Status LinuxCncController::Handshake() {
  StatusOr<std::string> hello = Ask("hello " + options_.connect_password + " hexcal 1.0");
  if (!hello.ok()) return hello.status();
  const std::vector<std::string> words = ReplyWords(*hello);
  if (words.size() < 2 || UpperCase(words[0]) != "HELLO" || UpperCase(words[1]) != "ACK")
    return Unexpected("hello", *hello, "'HELLO ACK ...'; a 'HELLO NAK' means the connect password was refused");
  if (words.size() >= 4) server_ = words[2] + " " + words[3];
  // Echo is on until this command is read, so it may come back as an echo,
  // and it sends no acknowledgement: verbose is off until the next one.
  if (Status s = client_.Send("set echo off"); !s.ok()) return Error(s.message());
  // Echoes of either command may come first (seen after a machine restart).
  StatusOr<std::string> reply = Ask("set verbose on");
  for (int echo = 0; echo < 2 && reply.ok(); ++echo) {
    const std::string line = UpperCase(JoinWords(ReplyWords(*reply)));
    if (line != "SET ECHO OFF" && line != "SET VERBOSE ON") break;
    reply = client_.ReadLine(options_.reply_timeout);
  }
  if (!reply.ok()) return Error("'set verbose on': " + reply.status().message());
  if (UpperCase(JoinWords(ReplyWords(*reply))) != "SET VERBOSE ACK")
    return Unexpected("set verbose on", *reply, "'SET VERBOSE ACK'");
  return Expect("set enable " + options_.enable_password, "SET ENABLE ACK", "the enable password was refused");
}

Status LinuxCncController::CheckUnits() {
  StatusOr<std::vector<std::string>> linear = AskWords("get user_linear_units", "USER_LINEAR_UNITS", 1);
  if (!linear.ok()) return linear.status();
  const std::optional<MachineUnit> unit = ParseMachineUnit((*linear)[0]);
  if (!unit)
    return Error("the machine's linear unit is " + Excerpt((*linear)[0]) +
                 "; hexcal needs [TRAJ] LINEAR_UNITS = mm or inch");
  unit_ = *unit;
  StatusOr<std::vector<std::string>> angular = AskWords("get user_angular_units", "USER_ANGULAR_UNITS", 1);
  if (!angular.ok()) return angular.status();
  if (UpperCase((*angular)[0]) != "DEG")
    return Error("the machine's angular unit is " + Excerpt((*angular)[0]) +
                 "; genhexkins reads A B C in degrees: set [TRAJ] ANGULAR_UNITS = degree");
  return Status::Ok();
}

StatusOr<bool> LinuxCncController::AllHomed() {
  StatusOr<std::vector<std::string>> homed = AskWords("get joint_homed", "JOINT_HOMED", 6);
  if (!homed.ok()) return homed.status();
  return std::all_of(homed->begin(), homed->end(), [](const std::string& word) { return UpperCase(word) == "YES"; });
}

Status LinuxCncController::WaitHomed(double seconds) {
  const Clock::time_point start = Clock::now();
  for (;;) {
    StatusOr<bool> all = AllHomed();
    if (!all.ok() || *all) return all.status();
    if (SecondsSince(start) >= seconds) break;
    std::this_thread::sleep_for(options_.poll_interval);
  }
  return Error("the joints were not homed within " + FixedNumber(seconds, 3) + " s");
}

Status LinuxCncController::HomeIfNeeded() {
  StatusOr<bool> homed = AllHomed();
  if (!homed.ok() || *homed) return homed.status();
  if (Status s = Expect("set mode manual", "SET MODE ACK"); !s.ok()) return s;
  if (Status s = Expect("set home -1", "SET HOME ACK"); !s.ok()) return s;
  return WaitHomed(options_.motion_timeout_seconds);
}

Status LinuxCncController::Rehome(const Vector6d& joints, double tolerance) {
  // Homing needs joint mode; a homed joint is homed again (seen with
  // LinuxCNC 2.9: at once when HOME_SEARCH_VEL is 0, so "homed" never reads
  // NO: the end is the joints at their new HOME).
  if (Status s = Expect("set mode manual", "SET MODE ACK"); !s.ok()) return s;
  if (Status s = Expect("set teleop_enable off", "SET TELEOP_ENABLE ACK"); !s.ok()) return s;
  if (Status s = Expect("set home -1", "SET HOME ACK"); !s.ok()) return s;
  const Clock::time_point start = Clock::now();
  for (;;) {
    StatusOr<bool> homed = AllHomed();
    if (!homed.ok()) return homed.status();
    StatusOr<Vector6d> now = AskSixNumbers("get joint_pos", "JOINT_POS");
    if (!now.ok()) return now.status();
    if (*homed && ((*now - joints).cwiseAbs().maxCoeff() <= tolerance)) break;
    if (SecondsSince(start) >= options_.motion_timeout_seconds) {
      StatusOr<std::string> error = NextMachineError();
      return Error("homing again did not bring the joints to " + SixText(joints) + " within " +
                   FixedNumber(options_.motion_timeout_seconds, 3) + " s: they are at " + SixText(*now) +
                   (error.ok() && !error->empty() ? " (" + *error + ")" : ""));
    }
    std::this_thread::sleep_for(options_.poll_interval);
  }
  last_joints_.reset();
  return Expect("set mode mdi", "SET MODE ACK");
}

StatusOr<std::string> LinuxCncController::NextMachineError() {
  StatusOr<std::string> reply = Ask("get error");
  // linuxcncrsh answers NAK when its error channel could not be read this
  // time (seen with a second client connected, the follower of
  // sim/machine_follower.h): asked again a few times.
  for (int retry = 0; retry < 5 && reply.ok() && UpperCase(JoinWords(ReplyWords(*reply))) == "GET NAK"; ++retry) {
    std::this_thread::sleep_for(options_.poll_interval);
    reply = Ask("get error");
  }
  if (!reply.ok()) return reply.status();
  const std::vector<std::string> words = ReplyWords(*reply);
  if (words.empty() || UpperCase(words[0]) != "ERROR") return Unexpected("get error", *reply, "'ERROR ...'");
  if (words.size() == 2 && UpperCase(words[1]) == "OK") return std::string();
  return JoinWords(std::vector<std::string>(words.begin() + 1, words.end()));
}

Status LinuxCncController::DiscardOldErrors() {
  // linuxcncrsh keeps the machine's messages since it started; a bounded
  // number, so a bound here that no machine reaches.
  for (int count = 0; count < 1000; ++count) {
    StatusOr<std::string> message = NextMachineError();
    if (!message.ok() || message->empty()) return message.status();
  }
  return Error("'get error' never answered 'ERROR OK'");
}

Status LinuxCncController::Open() {
  if (Status s = Handshake(); !s.ok()) return s;
  if (Status s = CheckUnits(); !s.ok()) return s;
  if (Status s = Expect("set estop off", "SET ESTOP ACK"); !s.ok()) return s;
  if (Status s = Expect("set machine on", "SET MACHINE ACK"); !s.ok()) return s;
  if (Status s = HomeIfNeeded(); !s.ok()) return s;
  if (Status s = Expect("set mode mdi", "SET MODE ACK"); !s.ok()) return s;
  return DiscardOldErrors();
}

Status LinuxCncController::SendMove(const Vector6d& from, const Vector6d& world, const std::string& text) {
  move_start_ = from;
  target_ = world;
  target_text_ = text;
  last_joints_.reset();
  std::string command = unit_ == MachineUnit::kInch ? "set mdi G20 G90 G53 G0" : "set mdi G21 G90 G53 G0";
  static const char* axes[6] = {"X", "Y", "Z", "A", "B", "C"};
  for (int k = 0; k < 6; ++k) command += std::string(" ") + axes[k] + FixedNumber(target_[k]);
  if (Status s =
          Expect(command, "SET MDI ACK", "the machine refused the move (is it in estop, off or not in MDI mode?)");
      !s.ok())
    return s;
  moving_ = true;
  return Status::Ok();
}

Status LinuxCncController::MoveTo(const Vector6d& pose) {
  moving_ = false;
  if (Status s = CheckPoseInWorkspace(robot_, pose); !s.ok()) return s;
  // Messages read now belong to earlier commands: WaitSettled's are this move's.
  if (Status s = DiscardOldErrors(); !s.ok()) return s;
  const Vector6d target = GenhexkinsWorldFromPose(robot_, pose, unit_);
  // Where the platform is, as the machine moves from it: the trajectory
  // planner's pose (exact where the last move ended or stopped; abs_act_pos
  // can be stale, PollMotion).
  StatusOr<Vector6d> here = AskSixNumbers("get abs_cmd_pos", "ABS_CMD_POS");
  if (!here.ok()) return here.status();
  // G0 is a straight line in X Y Z A B C, along which a leg can pass its
  // stroke between two poses within it (and stop the machine at a soft
  // limit): the move goes through waypoints that keep every leg within its
  // stroke (core/straight_moves.h), each sent as its own G0.
  const double scale = MachineUnitsPerRobotUnit(robot_, unit_);
  const auto motion = [scale](Vector6d world) {
    world.head<3>() /= scale;
    return world;
  };
  StraightMoveOptions options;
  options.vias = {MotionVectorFromPose(robot_.PoseFromVector(WorkspaceCentre(robot_)))};
  StatusOr<std::vector<Vector6d>> moves = PlanStraightMoves(robot_, motion(*here), motion(target), options);
  if (!moves.ok()) return Status::BadInput("pose " + PoseText(pose) + ": " + moves.status().message());
  Vector6d from = *here;
  for (size_t k = 0; k + 1 < moves->size(); ++k) {
    Vector6d waypoint = (*moves)[k];
    waypoint.head<3>() *= scale;
    const std::string text = "waypoint " + std::to_string(k + 1) + " of " + std::to_string(moves->size() - 1) +
                             " on the way to " + PoseText(pose);
    if (Status s = SendMove(from, waypoint, text); !s.ok()) return s;
    if (Status s = WaitSettled(0); !s.ok()) return s;
    from = waypoint;
  }
  return SendMove(from, target, PoseText(pose));
}

StatusOr<LinuxCncController::Motion> LinuxCncController::PollMotion() {
  StatusOr<std::vector<std::string>> program = AskWords("get program_status", "PROGRAM_STATUS", 1);
  if (!program.ok()) return program.status();
  Motion motion;
  motion.idle = UpperCase((*program)[0]) == "IDLE";
  if (!motion.idle) return motion;
  // In position: the trajectory planner's pose at the target and the joints
  // (the drives' feedback) still since the last poll. Not `abs_act_pos`: it
  // is genhexkins' forward kinematics of the joints, whose Newton iteration
  // fails at large rotations (genhexkins.fwd-kins-fail) and then reports a
  // stale pose (seen: the home pose at A = 35°, C = −60°). Nor hexcal's IK of
  // the target: the machine may run another geometry than the session's
  // robot (`verify` after a calibration was loaded).
  StatusOr<Vector6d> commanded = AskSixNumbers("get abs_cmd_pos", "ABS_CMD_POS");
  if (!commanded.ok()) return commanded.status();
  StatusOr<Vector6d> joints = AskSixNumbers("get joint_pos", "JOINT_POS");
  if (!joints.ok()) return joints.status();
  const bool still = last_joints_ && (*joints - *last_joints_).cwiseAbs().maxCoeff() <= options_.position_tolerance;
  last_joints_ = *joints;
  motion.in_position = still && (*commanded - target_).cwiseAbs().maxCoeff() <= options_.position_tolerance;
  return motion;
}

Status LinuxCncController::AbortMotion(Status why) {
  moving_ = false;
  const Status aborted = Expect("set abort", "SET ABORT ACK");
  const std::string what = aborted.ok() ? "motion stopped (set abort)" : "stopping it failed: " + aborted.message();
  return why.cancelled() ? Status::Cancelled(why.message() + "; " + what) : Error(why.message() + "; " + what);
}

Status LinuxCncController::WaitSettled(double settle_seconds) {
  if (!moving_) return Error("no move to wait for: the last MoveTo failed or none was made");
  const Clock::time_point start = Clock::now();
  double idle_since = -1;  // when the machine was first seen idle away from the target, seconds since start
  for (;;) {
    if (CancelRequested())
      return AbortMotion(
          Status::Cancelled("cancelled during the move to " + target_text_ + "; nothing recorded for this pose"));
    StatusOr<std::string> message = NextMachineError();
    if (!message.ok()) return message.status();
    if (!message->empty()) {
      // A move refused before it started (a target past a joint limit)
      // leaves the machine where it was; one stopped on the way (a soft
      // limit) leaves it where later moves fail too: the run stops (Usable).
      StatusOr<Vector6d> at = AskSixNumbers("get abs_cmd_pos", "ABS_CMD_POS");
      stuck_ = !at.ok() || (*at - move_start_).cwiseAbs().maxCoeff() > options_.position_tolerance;
      moving_ = false;
      return Error("the move to " + target_text_ + " failed: " + Excerpt(*message));
    }
    StatusOr<Motion> motion = PollMotion();
    if (!motion.ok()) return motion.status();
    if (motion->in_position) break;
    const double elapsed = SecondsSince(start);
    // A move that does not end is the machine's fault: stopped, and the run
    // with it (Usable), rather than sending the next pose after it.
    stuck_ = elapsed > options_.motion_timeout_seconds;
    if (stuck_)
      return AbortMotion(Status::Failed("the platform did not reach " + target_text_ + " within " +
                                        FixedNumber(options_.motion_timeout_seconds, 3) + " s"));
    // Idle right after the command may be a move not started yet; idle for
    // longer is a move that ended elsewhere (a soft limit, an abort).
    if (!motion->idle) idle_since = -1;
    if (motion->idle && idle_since < 0) idle_since = elapsed;
    stuck_ = motion->idle && elapsed - idle_since > options_.idle_grace_seconds;
    if (stuck_) return Error("the machine is idle but not at " + target_text_ + " = machine " + SixText(target_));
    std::this_thread::sleep_for(options_.poll_interval);
  }
  moving_ = false;
  stuck_ = false;  // a move that ended in position: the machine moves again
  return Settle(settle_seconds);
}

Status LinuxCncController::Settle(double seconds) {
  const Clock::time_point start = Clock::now();
  while (SecondsSince(start) < seconds) {
    if (CancelRequested()) return Status::Cancelled("cancelled while settling at " + target_text_);
    std::this_thread::sleep_for(std::min(std::chrono::duration<double>(options_.poll_interval),
                                         std::chrono::duration<double>(seconds - SecondsSince(start))));
  }
  return Status::Ok();
}

StatusOr<LegReadings> LinuxCncController::ReadLegs() {
  StatusOr<Vector6d> joints = AskSixNumbers("get joint_pos", "JOINT_POS");
  if (!joints.ok()) return joints.status();
  return ReadingsFromJoints(robot_, *joints, unit_);
}

}  // namespace

bool LinuxCncOptions::IsValid(std::string* error) const {
  if (connect_timeout.count() < 1 || reply_timeout.count() < 1 || poll_interval.count() < 1) {
    *error = "LinuxCNC time-outs and the poll interval must be at least 1 ms";
    return false;
  }
  if (!(motion_timeout_seconds > 0) || !(idle_grace_seconds > 0) || !(position_tolerance > 0)) {
    *error = "LinuxCNC motion time-out, idle grace and position tolerance must be positive";
    return false;
  }
  return true;
}

StatusOr<LinuxCncAddress> ParseLinuxCncUrl(const std::string& url) {
  const std::string scheme = "linuxcnc://";
  auto bad = [&](const std::string& problem) {
    return Status::BadInput("controller '" + url + "': " + problem + "; expected linuxcnc://HOST:PORT");
  };
  if (url.rfind(scheme, 0) != 0) return bad("not a linuxcnc:// URL");
  const std::string rest = url.substr(scheme.size());
  LinuxCncAddress address;
  size_t colon = rest.rfind(':');
  if (!rest.empty() && rest[0] == '[') {  // [IPv6]:PORT
    const size_t close = rest.find(']');
    if (close == std::string::npos || close + 1 >= rest.size() || rest[close + 1] != ':') return bad("bad [address]");
    address.host = rest.substr(1, close - 1);
    colon = close + 1;
  } else if (colon != std::string::npos) {
    address.host = rest.substr(0, colon);
  }
  if (colon == std::string::npos || address.host.empty()) return bad("no host or no port");
  const std::string port = rest.substr(colon + 1);
  const bool digits = std::all_of(port.begin(), port.end(), [](unsigned char c) { return std::isdigit(c); });
  if (port.empty() || port.size() > 5 || !digits) return bad("bad port");
  address.port = std::stoi(port);
  if (address.port < 1 || address.port > 65535) return bad("port out of 1..65535");
  return address;
}

StatusOr<std::unique_ptr<Controller>> OpenLinuxCncController(const LinuxCncAddress& address, const Robot& robot,
                                                             const LinuxCncOptions& options) {
  if (std::string error; !options.IsValid(&error)) return Status::BadInput(error);
  StatusOr<LineClient> client = LineClient::Connect(address.host, address.port, options.connect_timeout);
  if (!client.ok()) return client.status().Prefixed("LinuxCNC: ");  // no answer: I/O; a bad host: bad input
  auto controller = std::make_unique<LinuxCncController>(std::move(*client), robot, options);
  if (Status s = controller->Open(); !s.ok()) return s;
  return std::unique_ptr<Controller>(std::move(controller));
}

Status RehomeLinuxCnc(Controller& controller, const Vector6d& joints, double tolerance) {
  auto* machine = dynamic_cast<LinuxCncController*>(&controller);
  if (machine == nullptr)
    return Status::BadInput(controller.Describe() + " is not a LinuxCNC machine: nothing to home");
  return machine->Rehome(joints, tolerance);
}

}  // namespace hexcal::workflow

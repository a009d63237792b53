// The linuxcncrsh client against a fake linuxcncrsh: a thread serving canned
// replies on a loopback port, with the terminators the real one uses
// (../shared/devices.md: ACKs end "\n\r", get replies "\r\n", a NAK of a get
// is followed by an empty line).
#include "devices/linuxcnc_controller.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <deque>
#include <map>
#include <sstream>

#include "core/inverse_kinematics.h"
#include "devices/device_urls.h"
#include "devices/line_client.h"
#include "devices/linuxcnc_geometry.h"
#include "tests/fake_line_server.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal::workflow {
namespace {

using namespace std::chrono_literals;
using hexcal::testing::FakeLineServer;
using hexcal::testing::kCloseConnection;
using hexcal::testing::MatrixNear;
using hexcal::testing::Preset;

std::string SixNumbers(const std::string& key, const Vector6d& values) {
  std::string line = key;
  char number[32];
  for (int k = 0; k < 6; ++k) {
    std::snprintf(number, sizeof number, " %f", values[k]);  // linuxcncrsh prints %f
    line += number;
  }
  return line + "\r\n";
}

// A linuxcncrsh in front of a genhexkins machine with the robot's geometry:
// the replies of ../shared/devices.md, moves that take `running_polls` status
// polls, and test-set units, homing state, errors and overrides.
struct FakeLinuxCnc {
  Robot robot = Preset("inria-left-hand");
  MachineUnit unit = MachineUnit::kMillimetre;
  std::string linear_units = "MM", angular_units = "DEG";
  bool homed = true;
  int running_polls = 2;
  std::deque<std::string> errors{"Linear move on line 0 would exceed joint 0's positive limit"};  // an old one
  std::map<std::string, std::string> overrides;  // line -> reply, before the rules below
  Vector6d world = Vector6d::Zero(), joints = Vector6d::Zero();
  int polls_left = 0;
  bool moved = false;            // until the first move the platform is at home, the workspace centre
  std::vector<std::string> mdi;  // the moves received
  std::vector<Vector6d> worlds;  // the world poses moved to
  bool aborted = false;          // `set abort` was received

  std::string Reply(const std::string& line) {
    if (auto found = overrides.find(line); found != overrides.end()) return found->second;
    if (line == "hello EMC hexcal 1.0") return "HELLO ACK EMCNETSVR 1.1\r\n";
    if (line.rfind("hello", 0) == 0) return "HELLO NAK\r\n";
    if (line == "set echo off") return "set echo off\r\n";  // echoed: echo was still on
    if (line == "get user_linear_units") return "USER_LINEAR_UNITS " + linear_units + "\r\n";
    if (line == "get user_angular_units") return "USER_ANGULAR_UNITS " + angular_units + "\r\n";
    if (line == "get joint_homed")
      return homed ? "JOINT_HOMED YES YES YES YES YES YES\r\n" : "JOINT_HOMED NO YES NO YES YES YES\r\n";
    if (line == "set home -1") homed = true;
    if (line == "set abort") aborted = true;
    if (line == "get error") {
      if (errors.empty()) return "ERROR OK\r\n";
      const std::string message = "ERROR " + errors.front() + "\r\n";
      errors.pop_front();
      return message;
    }
    if (line == "get program_status") {
      if (polls_left > 0) --polls_left;
      return polls_left > 0 ? "PROGRAM_STATUS RUNNING\r\n" : "PROGRAM_STATUS IDLE\r\n";
    }
    if (line == "get abs_act_pos") {
      if (!moved) world = GenhexkinsWorldFromPose(robot, WorkspaceCentre(robot), unit);
      return SixNumbers("ABS_ACT_POS", polls_left > 0 ? Vector6d::Zero() : world);
    }
    if (line == "get abs_cmd_pos") {
      if (!moved) world = GenhexkinsWorldFromPose(robot, WorkspaceCentre(robot), unit);
      return SixNumbers("ABS_CMD_POS", world);
    }
    if (line == "get joint_pos") {
      if (!moved)
        joints =
            JointsFromReadings(robot, InverseKinematics(robot, robot.PoseFromVector(WorkspaceCentre(robot))), unit);
      return SixNumbers("JOINT_POS", joints);
    }
    if (line.rfind("set mdi ", 0) == 0) return Move(line);
    if (line == "quit") return kCloseConnection;
    if (line.rfind("set ", 0) == 0) {  // "set estop off" -> "SET ESTOP ACK"
      std::string word = line.substr(4, line.find(' ', 4) - 4);
      for (char& c : word) c = static_cast<char>(std::toupper(c));
      return "SET " + word + " ACK\n\r";
    }
    return "GET NAK\r\n\r\n";
  }

  // "set mdi G21 G90 G53 G0 X1 Y2 ...": the world pose, and the joints of genhexkins' IK.
  std::string Move(const std::string& line) {
    moved = true;
    mdi.push_back(line);
    std::istringstream words(line.substr(8));
    for (std::string word; words >> word;) {
      const size_t axis = std::string("XYZABC").find(word[0]);
      if (axis != std::string::npos) world[static_cast<int>(axis)] = std::stod(word.substr(1));
    }
    worlds.push_back(world);
    Pose pose;
    pose.position = world.head<3>() / MachineUnitsPerRobotUnit(robot, unit);
    pose.rotation = RotationFromEuler(world.tail<3>() * kPi / 180, EulerConvention::kXYZ);
    joints = JointsFromReadings(robot, InverseKinematics(robot, pose), unit);
    polls_left = running_polls;
    return "SET MDI ACK\n\r";
  }
};

LinuxCncOptions FastOptions() {
  LinuxCncOptions options;
  options.connect_timeout = 1000ms;
  options.reply_timeout = 300ms;
  options.motion_timeout_seconds = 1;
  options.idle_grace_seconds = 0.2;
  options.poll_interval = 1ms;
  return options;
}

struct FakeMachine {
  FakeLinuxCnc machine;
  FakeLineServer server{[this](const std::string& line) { return machine.Reply(line); }};
  LinuxCncAddress address() const { return {"127.0.0.1", server.port()}; }
  StatusOr<std::unique_ptr<Controller>> Open() {
    return OpenLinuxCncController(address(), machine.robot, FastOptions());
  }
};

Vector6d SomePose() {
  Vector6d pose;
  pose << 1, -2, 53, 3, -4, 5;
  return pose;
}

// The next line, or the error's message: a failed read fails the comparison
// that uses it instead of stopping the test.
std::string NextLine(LineClient& client) {
  StatusOr<std::string> line = client.ReadLine(500ms);
  return line.ok() ? *line : "error: " + line.status().message();
}

TEST(LineClient, ReadsLinesWithEitherTerminatorAndSkipsEmptyOnes) {
  FakeLineServer server([](const std::string& line) {
    if (line == "two") return std::string("SET A ACK\n\rGET B NAK\r\n\r\n");
    return std::string("ONE\r\n");
  });
  StatusOr<LineClient> client = LineClient::Connect("127.0.0.1", server.port(), 1000ms);
  ASSERT_TRUE(client.ok()) << client.status().message();
  ASSERT_TRUE(client->Send("one").ok());
  EXPECT_EQ(NextLine(*client), "ONE");
  ASSERT_TRUE(client->Send("two").ok());
  EXPECT_EQ(NextLine(*client), "SET A ACK");
  EXPECT_EQ(NextLine(*client), "GET B NAK");
  StatusOr<std::string> none = client->ReadLine(100ms);  // the empty line is not a reply
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("no reply within 0.1 s"), std::string::npos) << none.status().message();
}

TEST(LineClient, NamesAClosedConnectionARefusedOneAndAnOverlongLine) {
  FakeLineServer server([](const std::string& line) {
    if (line == "close") return std::string(kCloseConnection);
    return std::string(5000, 'x');
  });
  StatusOr<LineClient> client = LineClient::Connect("127.0.0.1", server.port(), 1000ms);
  ASSERT_TRUE(client.ok());
  ASSERT_TRUE(client->Send("garbage").ok());
  StatusOr<std::string> long_line = client->ReadLine(500ms);
  ASSERT_FALSE(long_line.ok());
  EXPECT_NE(long_line.status().message().find("longer than 4096 bytes"), std::string::npos);
  EXPECT_LT(long_line.status().message().size(), 200u);  // an excerpt, not the reply
  ASSERT_TRUE(client->Send("close").ok());
  StatusOr<std::string> closed = client->ReadLine(500ms);
  ASSERT_FALSE(closed.ok());
  EXPECT_NE(closed.status().message().find("closed by the peer"), std::string::npos) << closed.status().message();

  int port = 0;
  {
    FakeLineServer gone([](const std::string&) { return std::string(); });
    port = gone.port();
  }  // the port is closed now
  StatusOr<LineClient> refused = LineClient::Connect("127.0.0.1", port, 500ms);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("127.0.0.1:" + std::to_string(port) + ": cannot connect"),
            std::string::npos)
      << refused.status().message();
  EXPECT_EQ(refused.status().kind(), StatusKind::kIo);  // no machine answers: I/O, not a failed computation
}

TEST(LineClient, ExcerptIsShortAndPrintable) {
  EXPECT_EQ(Excerpt("SET MDI NAK"), "'SET MDI NAK'");
  EXPECT_EQ(Excerpt("a\x01"
                    "b"),
            "'a?b'");
  EXPECT_EQ(Excerpt(std::string(500, 'z'), 10), "'zzzzzzzzzz...'");
}

TEST(LinuxCncUrl, HostAndPort) {
  StatusOr<LinuxCncAddress> local = ParseLinuxCncUrl("linuxcnc://127.0.0.1:5007");
  ASSERT_TRUE(local.ok());
  EXPECT_EQ(local->host, "127.0.0.1");
  EXPECT_EQ(local->port, 5007);
  StatusOr<LinuxCncAddress> named = ParseLinuxCncUrl("linuxcnc://machine.lab:6000");
  ASSERT_TRUE(named.ok());
  EXPECT_EQ(named->host, "machine.lab");
  StatusOr<LinuxCncAddress> v6 = ParseLinuxCncUrl("linuxcnc://[::1]:5007");
  ASSERT_TRUE(v6.ok());
  EXPECT_EQ(v6->host, "::1");
  for (const char* bad : {"linuxcnc://", "linuxcnc://host", "linuxcnc://:5007", "linuxcnc://h:0", "linuxcnc://h:70000",
                          "linuxcnc://h:50x", "linuxcnc://[::1]5007"}) {
    StatusOr<LinuxCncAddress> address = ParseLinuxCncUrl(bad);
    ASSERT_FALSE(address.ok()) << bad;
    EXPECT_EQ(address.status().kind(), StatusKind::kBadInput);
    EXPECT_NE(address.status().message().find(std::string("controller '") + bad + "'"), std::string::npos);
  }
}

TEST(LinuxCncController, OpensMovesAndReadsTheJointsMinusOffsets) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok()) << machine.status().message();
  EXPECT_EQ((*machine)->Describe(), "LinuxCNC at 127.0.0.1:" + std::to_string(fake.server.port()) +
                                        " (EMCNETSVR 1.1, machine in mm, robot inria-left-hand in cm)");
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  ASSERT_TRUE((*machine)->WaitSettled(0).ok());
  StatusOr<LegReadings> legs = (*machine)->ReadLegs();
  ASSERT_TRUE(legs.ok()) << legs.status().message();
  const Robot& robot = fake.machine.robot;
  // %f prints 1e-6 mm: 1e-7 cm.
  EXPECT_TRUE(MatrixNear(*legs, InverseKinematics(robot, robot.PoseFromVector(SomePose())), 1e-6));

  const std::vector<std::string> sent = fake.server.Received();
  const std::vector<std::string> opening(sent.begin(), sent.begin() + 10);
  EXPECT_EQ(opening, (std::vector<std::string>{"hello EMC hexcal 1.0", "set echo off", "set verbose on",
                                               "set enable EMCTOO", "get user_linear_units", "get user_angular_units",
                                               "set estop off", "set machine on", "get joint_homed", "set mode mdi"}));
  EXPECT_NE(std::find(sent.begin(), sent.end(), "set mdi G21 G90 G53 G0 X10 Y-20 Z530 A3 B-4 C5"), sent.end());
}

TEST(LinuxCncController, HomesAMachineThatIsNotHomed) {
  FakeMachine fake;
  fake.machine.homed = false;
  ASSERT_TRUE(fake.Open().ok());
  const std::vector<std::string> sent = fake.server.Received();
  auto position = [&](const std::string& line) { return std::find(sent.begin(), sent.end(), line) - sent.begin(); };
  EXPECT_LT(position("set mode manual"), position("set home -1"));
  EXPECT_LT(position("set home -1"), position("set mode mdi"));
  EXPECT_LT(position("set mode mdi"), static_cast<long>(sent.size()));
}

TEST(LinuxCncController, InchMachineGetsG20AndInches) {
  FakeMachine fake;
  fake.machine.linear_units = "INCH";
  fake.machine.unit = MachineUnit::kInch;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok()) << machine.status().message();
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  ASSERT_TRUE((*machine)->WaitSettled(0).ok());
  const std::vector<std::string> sent = fake.server.Received();
  EXPECT_NE(
      std::find_if(sent.begin(), sent.end(),
                   [](const std::string& line) { return line.rfind("set mdi G20 G90 G53 G0 X0.393700787", 0) == 0; }),
      sent.end());
  const Robot& robot = fake.machine.robot;
  // %f prints 1e-6 inch: 2.5e-6 cm.
  StatusOr<LegReadings> legs = (*machine)->ReadLegs();
  ASSERT_TRUE(legs.ok()) << legs.status().message();
  EXPECT_TRUE(MatrixNear(*legs, InverseKinematics(robot, robot.PoseFromVector(SomePose())), 5e-6));
}

// The message of opening a fake machine with one reply replaced.
std::string OpenError(const std::string& line, const std::string& reply) {
  FakeMachine fake;
  fake.machine.overrides[line] = reply;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  EXPECT_FALSE(machine.ok()) << line;
  return machine.ok() ? std::string() : machine.status().message();
}

TEST(LinuxCncController, OpeningErrorsNameTheCommandAndTheReply) {
  EXPECT_NE(OpenError("hello EMC hexcal 1.0", "HELLO NAK\r\n").find("connect password was refused"), std::string::npos);
  EXPECT_NE(OpenError("set enable EMCTOO", "SET ENABLE NAK\n\r")
                .find("'set enable EMCTOO' was answered 'SET ENABLE NAK' (expected 'SET ENABLE ACK'): "
                      "the enable password was refused"),
            std::string::npos);
  EXPECT_NE(OpenError("get user_linear_units", "USER_LINEAR_UNITS CUSTOM\r\n")
                .find("the machine's linear unit is 'CUSTOM'; hexcal needs [TRAJ] LINEAR_UNITS = mm or inch"),
            std::string::npos);
  EXPECT_NE(OpenError("get user_angular_units", "USER_ANGULAR_UNITS RAD\r\n").find("ANGULAR_UNITS = degree"),
            std::string::npos);
  EXPECT_NE(OpenError("set machine on", "SET MACHINE NAK\n\r").find("'set machine on' was answered 'SET MACHINE NAK'"),
            std::string::npos);
  EXPECT_NE(OpenError("get joint_homed", "JOINT_HOMED YES\r\n").find("(expected JOINT_HOMED and 6 value(s))"),
            std::string::npos);
  EXPECT_NE(OpenError("set verbose on", "").find("'set verbose on': 127.0.0.1:"), std::string::npos);
  EXPECT_NE(OpenError("set verbose on", "").find("no reply within 0.3 s"), std::string::npos);
  const std::string garbage = OpenError("get user_linear_units", std::string(3000, 'q') + "\r\n");
  EXPECT_NE(garbage.find("'qqqq"), std::string::npos);
  EXPECT_LT(garbage.size(), 300u);  // the reply is quoted as a short excerpt
}

TEST(LinuxCncController, AMoveTheMachineRefusesFailsNamingItsMessage) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  fake.machine.running_polls = 1000;
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  fake.machine.errors.push_back("Linear move on line 0 would exceed joint 2's positive limit");
  Status settled = (*machine)->WaitSettled(0);
  ASSERT_FALSE(settled.ok());
  EXPECT_NE(settled.message().find("the move to (1, -2, 53, 3, -4, 5) failed: 'Linear move on line 0 would exceed "
                                   "joint 2's positive limit'"),
            std::string::npos)
      << settled.message();
  // The old error of FakeLinuxCnc was read away when the machine opened.
  EXPECT_EQ(settled.message().find("joint 0"), std::string::npos);
  // The fake's planner pose jumped to the target: the move stopped on its
  // way, where later moves would fail too.
  EXPECT_FALSE((*machine)->Usable());

  // Refused before it started (the planner still at the start): usable.
  fake.machine.running_polls = 1;
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  ASSERT_TRUE((*machine)->WaitSettled(0).ok());
  fake.machine.running_polls = 1000;
  Vector6d next = SomePose();
  next[0] = 0;
  fake.machine.overrides["get abs_cmd_pos"] = SixNumbers("ABS_CMD_POS", fake.machine.world);
  ASSERT_TRUE((*machine)->MoveTo(next).ok());
  fake.machine.errors.push_back("Linear move on line 0 would exceed joint 2's positive limit");
  EXPECT_FALSE((*machine)->WaitSettled(0).ok());
  EXPECT_TRUE((*machine)->Usable());
}

// genhexkins' forward kinematics fails at large rotations and then reports a
// stale world pose (the home pose, seen at A = 35°, C = −60°): the planner's
// pose and still joints, not `abs_act_pos`, say whether the platform arrived
// and where the next move starts.
TEST(LinuxCncController, AStaleActualPoseIsNotTrusted) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  fake.machine.overrides["get abs_act_pos"] = "ABS_ACT_POS 0 0 535 0 0 0\r\n";
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  Status settled = (*machine)->WaitSettled(0);
  EXPECT_TRUE(settled.ok()) << settled.message();
  Vector6d next = SomePose();
  next[0] = -1;
  ASSERT_TRUE((*machine)->MoveTo(next).ok());
  EXPECT_TRUE((*machine)->WaitSettled(0).ok());
  // One straight move from where the platform is (SomePose), not from home.
  EXPECT_EQ(fake.machine.mdi.size(), 2u);
}

// Ctrl-C during a move (issue 33): the motion is stopped with `set abort`
// at once, not after the 120 s time-out.
TEST(LinuxCncController, ACancelStopsTheMotion) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  fake.machine.running_polls = 1000000;
  std::atomic<bool> cancel{false};
  (*machine)->SetCancelFlag(&cancel);
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  cancel = true;
  const auto start = std::chrono::steady_clock::now();
  Status stopped = (*machine)->WaitSettled(0);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 500ms);
  EXPECT_TRUE(stopped.cancelled()) << stopped.message();
  EXPECT_NE(stopped.message().find("cancelled during the move to (1, -2, 53, 3, -4, 5); nothing recorded for this "
                                   "pose; motion stopped (set abort)"),
            std::string::npos)
      << stopped.message();
  EXPECT_TRUE(fake.machine.aborted);
  EXPECT_TRUE((*machine)->Usable());
}

// A move that does not end is stopped too, and the controller says it should
// take no more moves (the acquire run stops instead of timing out per pose).
TEST(LinuxCncController, ATimedOutMoveIsStoppedAndTheControllerNotUsable) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  fake.machine.overrides["get program_status"] = "PROGRAM_STATUS RUNNING\r\n";
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  Status slow = (*machine)->WaitSettled(0);
  EXPECT_EQ(slow.kind(), StatusKind::kFailed);
  EXPECT_NE(slow.message().find("within 1 s; motion stopped (set abort)"), std::string::npos) << slow.message();
  EXPECT_TRUE(fake.machine.aborted);
  EXPECT_FALSE((*machine)->Usable());
}

TEST(LinuxCncController, MoveErrors) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  Vector6d far = SomePose();
  far[2] = 80;  // out of the strokes
  Status unreachable = (*machine)->MoveTo(far);
  EXPECT_EQ(unreachable.kind(), StatusKind::kBadInput);
  EXPECT_NE(unreachable.message().find("is out of the robot's workspace"), std::string::npos);
  EXPECT_FALSE((*machine)->WaitSettled(0).ok());  // no move to wait for

  fake.machine.overrides["get program_status"] = "PROGRAM_STATUS RUNNING\r\n";
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  Status slow = (*machine)->WaitSettled(0);
  EXPECT_NE(slow.message().find("did not reach (1, -2, 53, 3, -4, 5) within 1 s"), std::string::npos) << slow.message();

  fake.machine.overrides["get program_status"] = "PROGRAM_STATUS IDLE\r\n";
  fake.machine.overrides["get abs_cmd_pos"] = "ABS_CMD_POS 0 0 535 0 0 0\r\n";  // reachable, not the target
  ASSERT_TRUE((*machine)->MoveTo(SomePose()).ok());
  Status elsewhere = (*machine)->WaitSettled(0);
  EXPECT_NE(elsewhere.message().find("idle but not at (1, -2, 53, 3, -4, 5)"), std::string::npos)
      << elsewhere.message();
  fake.machine.overrides.erase("get abs_cmd_pos");

  fake.machine.overrides["get joint_pos"] = "JOINT_POS 1 2 3 4 5 nan\r\n";
  StatusOr<LegReadings> nan = (*machine)->ReadLegs();
  EXPECT_NE(nan.status().message().find("'get joint_pos': value 6 is not a number: 'nan'"), std::string::npos);
  fake.machine.overrides["get joint_pos"] = "GET JOINT_POS NAK\r\n\r\n";
  EXPECT_NE((*machine)->ReadLegs().status().message().find("was answered 'GET JOINT_POS NAK'"), std::string::npos);
  fake.machine.overrides["get joint_pos"] = "";
  EXPECT_NE((*machine)->ReadLegs().status().message().find("'get joint_pos': 127.0.0.1:"), std::string::npos);
}

// A sideways move between two poses whose strokes are set to just hold
// them: a leg is shortest where it is most upright, between the two, so the
// straight G0 would leave its stroke (checked here, so the case cannot pass
// vacuously). The controller sends waypoints instead, and every straight
// segment it sends keeps every leg within its stroke (sampled densely here).
TEST(LinuxCncController, AMoveWhosePathLeavesAStrokeGoesThroughWaypoints) {
  FakeMachine fake;
  Robot& robot = fake.machine.robot;
  Vector6d from, to;
  from << -6, -6, 53.5, 0, 0, 0;
  to << 6, 6, 53.5, 0, 0, 10;
  const LegReadings a = InverseKinematics(robot, robot.PoseFromVector(from));
  const LegReadings b = InverseKinematics(robot, robot.PoseFromVector(to));
  for (int i = 0; i < kNumLegs; ++i) {
    robot.legs[i].stroke_min = std::min(a[i], b[i]) - 1e-3;
    robot.legs[i].stroke_max = std::max(a[i], b[i]) + 1e-3;
  }
  const MachineUnit mm = MachineUnit::kMillimetre;
  // The largest excess over any stroke along a straight G0 between two world poses.
  const auto excess = [&](const Vector6d& start, const Vector6d& end) {
    double worst = -1e9;
    for (int k = 0; k <= 1000; ++k) {
      const LegReadings legs =
          InverseKinematics(robot, PoseFromGenhexkinsWorld(robot, start + (end - start) * (k / 1000.0), mm));
      for (int i = 0; i < kNumLegs; ++i)
        worst = std::max({worst, legs[i] - robot.legs[i].stroke_max, robot.legs[i].stroke_min - legs[i]});
    }
    return worst;
  };
  ASSERT_GT(excess(GenhexkinsWorldFromPose(robot, from, mm), GenhexkinsWorldFromPose(robot, to, mm)), 0.01);
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok()) << machine.status().message();
  ASSERT_TRUE((*machine)->MoveTo(from).ok());
  ASSERT_TRUE((*machine)->WaitSettled(0).ok());
  fake.machine.worlds = {GenhexkinsWorldFromPose(robot, from, mm)};
  Status moved = (*machine)->MoveTo(to);
  ASSERT_TRUE(moved.ok()) << moved.message();
  ASSERT_TRUE((*machine)->WaitSettled(0).ok());
  ASSERT_GE(fake.machine.worlds.size(), 3u);  // from, a waypoint at least, to
  EXPECT_NE(fake.machine.mdi.back().find("X60 Y60 Z535 A0 B0 C10"), std::string::npos) << fake.machine.mdi.back();
  for (size_t k = 1; k < fake.machine.worlds.size(); ++k)
    EXPECT_LE(excess(fake.machine.worlds[k - 1], fake.machine.worlds[k]), 1e-4 * 3.5) << "segment " << k;
}

TEST(LinuxCncController, AMdiNakIsNamed) {
  FakeMachine fake;
  StatusOr<std::unique_ptr<Controller>> machine = fake.Open();
  ASSERT_TRUE(machine.ok());
  fake.machine.overrides["set mdi G21 G90 G53 G0 X10 Y-20 Z530 A3 B-4 C5"] = "SET MDI NAK\n\r";
  Status refused = (*machine)->MoveTo(SomePose());
  EXPECT_NE(refused.message().find("was answered 'SET MDI NAK' (expected 'SET MDI ACK'): the machine refused the move"),
            std::string::npos)
      << refused.message();
}

TEST(LinuxCncController, OpenControllerNeedsTheRobot) {
  FakeMachine fake;
  const std::string url = "linuxcnc://127.0.0.1:" + std::to_string(fake.server.port());
  StatusOr<std::unique_ptr<Controller>> without = OpenController(url);
  ASSERT_FALSE(without.ok());
  EXPECT_NE(without.status().message().find("needs the session's robot"), std::string::npos);
  ControllerOptions options;
  options.robot = std::make_shared<const Robot>(fake.machine.robot);
  StatusOr<std::unique_ptr<Controller>> with = OpenController(url, options);
  EXPECT_TRUE(with.ok()) << with.status().message();
}

}  // namespace
}  // namespace hexcal::workflow

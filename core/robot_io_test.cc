#include "core/robot_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "core/presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::SourceDir;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::Uniform;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Exact comparison, field by field, down to the bits of every double.
::testing::AssertionResult RobotsIdentical(const Robot& a, const Robot& b) {
  auto fail = [](const std::string& what) { return ::testing::AssertionFailure() << what; };
  if (a.name != b.name) return fail("name: " + a.name + " vs " + b.name);
  if (a.length_unit != b.length_unit) return fail("length_unit");
  if (a.euler != b.euler) return fail("euler");
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& p = a.legs[i];
    const Leg& q = b.legs[i];
    for (int k = 0; k < 3; ++k) {
      if (!SameBits(p.a_in_base[k], q.a_in_base[k])) return fail("legs[" + std::to_string(i) + "].a");
      if (!SameBits(p.b_in_platform[k], q.b_in_platform[k])) {
        return fail("legs[" + std::to_string(i) + "].b");
      }
    }
    if (!SameBits(p.offset, q.offset) || !SameBits(p.stroke_min, q.stroke_min) ||
        !SameBits(p.stroke_max, q.stroke_max)) {
      return fail("legs[" + std::to_string(i) + "] l or stroke");
    }
  }
  auto same_optional = [](const std::optional<double>& x, const std::optional<double>& y) {
    return x.has_value() == y.has_value() && (!x || SameBits(*x, *y));
  };
  if (!same_optional(a.limits.base_joint_max_deg, b.limits.base_joint_max_deg) ||
      !same_optional(a.limits.platform_joint_max_deg, b.limits.platform_joint_max_deg) ||
      !same_optional(a.limits.leg_min_distance, b.limits.leg_min_distance)) {
    return fail("limits");
  }
  const auto& mode_a = a.limits.assembly_mode;
  const auto& mode_b = b.limits.assembly_mode;
  if (mode_a.has_value() != mode_b.has_value()) return fail("assembly_mode");
  if (mode_a) {
    for (int k = 0; k < 6; ++k) {
      if (!SameBits(mode_a->pose[k], mode_b->pose[k])) return fail("assembly_mode.pose " + std::to_string(k));
    }
    if (!SameBits(mode_a->min_det_ratio, mode_b->min_det_ratio)) return fail("assembly_mode.min_det_ratio");
  }
  if (a.limits.pose_box.has_value() != b.limits.pose_box.has_value()) return fail("pose_box");
  if (a.limits.pose_box) {
    for (int k = 0; k < 6; ++k) {
      const auto& x = a.limits.pose_box->bounds[k];
      const auto& y = b.limits.pose_box->bounds[k];
      if (x.has_value() != y.has_value() || (x && (!SameBits(x->min, y->min) || !SameBits(x->max, y->max)))) {
        return fail("pose_box bound " + std::to_string(k));
      }
    }
  }
  return ::testing::AssertionSuccess();
}

Robot LoadOrDie(const std::string& path_or_preset) {
  StatusOr<Robot> robot = LoadRobot(path_or_preset);
  EXPECT_TRUE(robot.ok()) << robot.status().message();
  return robot.ok() ? *robot : Robot{};
}

TEST(RobotIoTest, PresetNamesListTheEmbeddedFiles) {
  EXPECT_EQ(PresetNames(), (std::vector<std::string>{"deltalab-table", "inria-left-hand"}));
}

TEST(RobotIoTest, InriaPresetHoldsTable1OfThePaper) {
  const Robot robot = LoadOrDie("inria-left-hand");
  EXPECT_EQ(robot.name, "inria-left-hand");
  EXPECT_EQ(robot.length_unit, LengthUnit::kCentimetre);
  EXPECT_EQ(robot.euler, EulerConvention::kXYZ);
  EXPECT_EQ(robot.legs[0].a_in_base, Eigen::Vector3d(-9.7, 9.1, 0));
  EXPECT_EQ(robot.legs[2].a_in_base, Eigen::Vector3d(12.76, 3.9, 0));
  EXPECT_EQ(robot.legs[3].b_in_platform, Eigen::Vector3d(4.822, -6.248, 0));
  EXPECT_EQ(robot.legs[5].b_in_platform, Eigen::Vector3d(-7.822, -1.052, 0));
  EXPECT_EQ(robot.legs[1].offset, 52.2496);
  EXPECT_EQ(robot.legs[4].offset, 52.2568);
  for (const Leg& leg : robot.legs) {
    EXPECT_EQ(leg.stroke_min, 0);
    EXPECT_EQ(leg.stroke_max, 3.5);
  }
  // Limits chosen so the boundary set is the paper's 44 poses (see the preset's comment).
  EXPECT_EQ(robot.limits.base_joint_max_deg, 50);
  EXPECT_EQ(robot.limits.platform_joint_max_deg, 50);
  EXPECT_EQ(robot.limits.leg_min_distance, 0.5);
  ASSERT_TRUE(robot.limits.assembly_mode);
  EXPECT_EQ(robot.limits.assembly_mode->pose, (Vector6d() << 0, 0, 53.5, 0, 0, 0).finished());
  EXPECT_EQ(robot.limits.assembly_mode->min_det_ratio, 0.1);
  ASSERT_TRUE(robot.limits.pose_box && robot.limits.pose_box->IsComplete());
  EXPECT_EQ(robot.limits.pose_box->bounds[2]->min, 47);
  EXPECT_EQ(robot.limits.pose_box->bounds[2]->max, 56);
  EXPECT_EQ(robot.limits.pose_box->bounds[5]->min, -60);
  // Random poses are drawn in the paper-like central box, inside the pose box.
  ASSERT_TRUE(robot.limits.sampling_box && robot.limits.sampling_box->IsComplete());
  const PoseBox sampling = *robot.limits.SamplingBox();
  EXPECT_EQ(sampling.bounds[0]->min, -5);
  EXPECT_EQ(sampling.bounds[2]->min, 50);  // the pose box's 47 does not widen it
  EXPECT_EQ(sampling.bounds[2]->max, 56);  // the pose box's 56 narrows the sampling box's 57
  EXPECT_EQ(sampling.bounds[5]->max, 20);
}

TEST(RobotIoTest, DeltalabPresetHasThePublishedDimensions) {
  const Robot robot = LoadOrDie("deltalab-table");
  EXPECT_EQ(robot.length_unit, LengthUnit::kMillimetre);
  EXPECT_EQ(robot.euler, EulerConvention::kXYZ);
  const double base_angles[] = {-15, 15, 105, 135, 225, 255};
  const double platform_angles[] = {-45, 45, 75, 165, 195, 285};
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const double t_a = DegToRad(base_angles[i]);
    const double t_b = DegToRad(platform_angles[i]);
    EXPECT_TRUE(testing::MatrixNear(leg.a_in_base, Eigen::Vector3d(270 * std::cos(t_a), 270 * std::sin(t_a), 0), 1e-6))
        << "leg " << i;
    EXPECT_TRUE(
        testing::MatrixNear(leg.b_in_platform, Eigen::Vector3d(195 * std::cos(t_b), 195 * std::sin(t_b), 0), 1e-6))
        << "leg " << i;
    // The paper's leg lengths: 345 to 485 mm.
    EXPECT_EQ(leg.offset + leg.stroke_min, 345);
    EXPECT_EQ(leg.offset + leg.stroke_max, 485);
  }
  EXPECT_EQ(robot.limits.base_joint_max_deg, 50);
  EXPECT_EQ(robot.limits.leg_min_distance, 10);
  ASSERT_TRUE(robot.limits.pose_box && robot.limits.pose_box->IsComplete());
  EXPECT_EQ(robot.limits.pose_box->bounds[5]->max, 50);
}

TEST(RobotIoTest, PresetsSurviveSaveAndLoadExactly) {
  TempDir dir;
  for (const std::string& name : PresetNames()) {
    const Robot robot = LoadOrDie(name);
    const std::string path = dir.File(name + ".yaml");
    ASSERT_TRUE(SaveRobot(robot, path).ok());
    const Robot reloaded = LoadOrDie(path);
    EXPECT_TRUE(RobotsIdentical(robot, reloaded)) << name;
    EXPECT_EQ(RobotToYaml(reloaded), ReadTextFile(path)) << name;
  }
}

TEST(RobotIoTest, ArbitraryDoublesSurviveSaveAndLoadExactly) {
  Robot robot = LoadOrDie("inria-left-hand");
  for (Leg& leg : robot.legs) {
    leg.a_in_base += Eigen::Vector3d(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1e-9, 1e-9));
    leg.b_in_platform *= 1.0 / 3.0;
    leg.offset = 52 + Uniform(-0.5, 0.5);
    leg.stroke_max = 0.1 + 0.2 + Uniform(1, 4);
  }
  robot.limits.leg_min_distance = 1e-300;
  robot.limits.assembly_mode->pose[0] = Uniform(-1, 1);
  robot.limits.assembly_mode->min_det_ratio = 0.1 + 0.2 / 3;
  robot.limits.pose_box->bounds[1].reset();
  robot.limits.base_joint_max_deg.reset();
  robot.euler = EulerConvention::kZYX;
  robot.length_unit = LengthUnit::kMetre;
  StatusOr<Robot> reloaded = ParseRobotYaml(RobotToYaml(robot), "generated");
  ASSERT_TRUE(reloaded.ok()) << reloaded.status().message() << "\n" << RobotToYaml(robot);
  EXPECT_TRUE(RobotsIdentical(robot, *reloaded));
}

TEST(RobotIoTest, RobotWithoutLimitsWritesNoLimitsBlock) {
  Robot robot = LoadOrDie("inria-left-hand");
  robot.limits = RobotLimits{};
  const std::string yaml = RobotToYaml(robot);
  EXPECT_THAT(yaml, ::testing::Not(HasSubstr("limits")));
  StatusOr<Robot> reloaded = ParseRobotYaml(yaml, "generated");
  ASSERT_TRUE(reloaded.ok()) << reloaded.status().message();
  EXPECT_TRUE(RobotsIdentical(robot, *reloaded));
}

TEST(RobotIoTest, NamesThatLookLikeOtherYamlAreQuotedAndSurvive) {
  Robot robot = LoadOrDie("inria-left-hand");
  for (const std::string name :
       {"null", "~", "true", "123", " padded ", "a: b", "#hash", "- dash", "say \"hi\"", "two\nlines", "réel"}) {
    robot.name = name;
    StatusOr<Robot> reloaded = ParseRobotYaml(RobotToYaml(robot), "generated");
    ASSERT_TRUE(reloaded.ok()) << name << ": " << reloaded.status().message();
    EXPECT_EQ(reloaded->name, name);
  }
}

TEST(RobotIoTest, CalibrationBlockIsAcceptedAndIgnored) {
  const std::string text = RobotToYaml(LoadOrDie("inria-left-hand")) +
                           "calibration:\n"
                           "  date: 2024-05-01\n"
                           "  poses: plan.csv\n"
                           "  rms_residual: 0.0012\n"
                           "  solver: {iterations: 12, termination: CONVERGENCE}\n";
  StatusOr<Robot> robot = ParseRobotYaml(text, "calibrated.yaml");
  ASSERT_TRUE(robot.ok()) << robot.status().message();
  EXPECT_TRUE(RobotsIdentical(*robot, LoadOrDie("inria-left-hand")));
}

TEST(RobotIoTest, NegativeOffsetIsAllowedWhileTheLegStaysLong) {
  std::string text = RobotToYaml(LoadOrDie("inria-left-hand"));
  const std::string from = "l: 52.2496, stroke: [0, 3.5]";
  text.replace(text.find(from), from.size(), "l: -1, stroke: [2, 5]");
  StatusOr<Robot> robot = ParseRobotYaml(text, "negative_offset.yaml");
  ASSERT_TRUE(robot.ok()) << robot.status().message();
  EXPECT_EQ(robot->legs[0].offset, -1);
}

TEST(RobotIoTest, LimitsAreOptional) {
  std::string text = RobotToYaml(LoadOrDie("inria-left-hand"));
  text = text.substr(0, text.find("limits:")) + "limits:\n  pose_box: {z: [50, 57]}\n";
  StatusOr<Robot> robot = ParseRobotYaml(text, "partial.yaml");
  ASSERT_TRUE(robot.ok()) << robot.status().message();
  EXPECT_FALSE(robot->limits.base_joint_max_deg);
  EXPECT_FALSE(robot->limits.leg_min_distance);
  ASSERT_TRUE(robot->limits.pose_box);
  EXPECT_FALSE(robot->limits.pose_box->bounds[0]);
  EXPECT_EQ(robot->limits.pose_box->bounds[2]->max, 57);
}

// Restores the working directory even when an ASSERT returns early.
class ScopedWorkingDirectory {
 public:
  explicit ScopedWorkingDirectory(const std::filesystem::path& dir) : previous_(std::filesystem::current_path()) {
    std::filesystem::current_path(dir);
  }
  ~ScopedWorkingDirectory() { std::filesystem::current_path(previous_); }

 private:
  std::filesystem::path previous_;
};

TEST(RobotIoTest, AFileWinsOverAPresetOfTheSameName) {
  TempDir dir;
  ScopedWorkingDirectory in_dir(dir.path());
  Robot robot = LoadOrDie("inria-left-hand");
  robot.name = "local-copy";
  ASSERT_TRUE(SaveRobot(robot, "inria-left-hand").ok());
  EXPECT_EQ(LoadOrDie("inria-left-hand").name, "local-copy");
}

TEST(RobotIoTest, UnknownNameListsThePresets) {
  StatusOr<Robot> robot = LoadRobot("inria-right-hand");
  ASSERT_FALSE(robot.ok());
  EXPECT_EQ(robot.status().message(),
            "robot 'inria-right-hand': no such file and no preset of that name "
            "(presets: deltalab-table, inria-left-hand)");
}

TEST(RobotIoTest, AFolderIsNotARobotFile) {
  TempDir dir;
  StatusOr<Robot> robot = LoadRobot(dir.path().string());
  ASSERT_FALSE(robot.ok());
  EXPECT_EQ(robot.status().message(), "robot file '" + dir.path().string() + "': is a directory, not a file");
}

TEST(RobotIoTest, SaveIntoAMissingFolderFails) {
  TempDir dir;
  const std::string path = dir.File("missing/robot.yaml");
  Status saved = SaveRobot(LoadOrDie("inria-left-hand"), path);
  ASSERT_FALSE(saved.ok());
  EXPECT_THAT(saved.message(), HasSubstr(path));
}

// Each tests/data/bad_robots/*.yaml starts with "# expect: <text>"; loading
// it must fail with a message naming the file and containing <text>.
TEST(RobotIoTest, EveryBadRobotFileFailsWithItsExpectedMessage) {
  const std::filesystem::path folder = SourceDir() / "tests" / "data" / "bad_robots";
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string path = entry.path().string();
    const std::string text = ReadTextFile(path);
    const std::string marker = "# expect: ";
    ASSERT_EQ(text.rfind(marker, 0), 0u) << path << " does not start with '" << marker << "'";
    const std::string expected = text.substr(marker.size(), text.find('\n') - marker.size());
    ASSERT_FALSE(expected.empty()) << path;

    StatusOr<Robot> robot = LoadRobot(path);
    ++checked;
    if (robot.ok()) {
      ADD_FAILURE() << path << " loaded without error; expected: " << expected;
      continue;
    }
    EXPECT_THAT(robot.status().message(), HasSubstr("robot file '" + path + "': "));
    EXPECT_THAT(robot.status().message(), HasSubstr(expected)) << path;
  }
  EXPECT_GE(checked, 16) << "bad robot files found in " << folder;
}

// Issue 13: a robot path naming a text file (/etc/passwd) printed the whole
// file in "expected a mapping ..., found '...'"; now a short excerpt.
TEST(RobotIoTest, ATextFileIsQuotedAsAShortExcerptOnly) {
  TempDir dir;
  const std::string path = dir.File("passwd");
  WriteTextFile(path, "root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:SECRET:/usr/sbin:/usr/sbin/nologin\n");
  StatusOr<Robot> robot = LoadRobot(path);
  ASSERT_FALSE(robot.ok());
  EXPECT_THAT(robot.status().message(), HasSubstr("found 'root:x:0:0:root:/root:/b...'"));
  EXPECT_THAT(robot.status().message(), ::testing::Not(HasSubstr("SECRET")));
}

}  // namespace
}  // namespace hexcal

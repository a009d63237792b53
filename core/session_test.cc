// The session folder: init, session.yaml round trip, and legs.csv errors that
// name the file and the line.
#include "core/session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

SessionConfig Config() {
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.camera = "camera.yaml";
  config.target = "aprilgrid-6x6";
  return config;
}

// A session with images a.png, b.png, c.png (their content does not matter here).
std::string MakeSession(const TempDir& temp) {
  const std::string dir = temp.File("s");
  EXPECT_TRUE(InitSession(dir, Config()).ok());
  for (const char* name : {"a.png", "b.png", "c.png"}) WriteTextFile(dir + "/images/" + name, "x");
  return dir;
}

std::string LegsError(const std::string& dir, const std::string& legs) {
  WriteTextFile(dir + "/legs.csv", legs);
  return testing::ErrorMessage(LoadSessionLegs(dir), legs);
}

TEST(Session, InitCreatesTheFolderAndRefusesASecondInit) {
  TempDir temp;
  const std::string dir = temp.File("s");
  ASSERT_TRUE(InitSession(dir, Config()).ok());
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/images"));
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/results"));
  const Status again = InitSession(dir, Config());
  ASSERT_FALSE(again.ok());
  EXPECT_THAT(again.message(), HasSubstr("session.yaml: exists"));
}

TEST(Session, ConfigRoundTripsWithFrames) {
  TempDir temp;
  const std::string dir = temp.File("s");
  SessionConfig config = Config();
  config.noise = {0.002, 0.03, 0.004};
  ASSERT_TRUE(InitSession(dir, config).ok());
  config.base_from_camera = PoseFromVector((Vector6d() << 1, 2, 120, 178, 3, 40).finished(), EulerConvention::kXYZ);
  config.platform_from_target = PoseFromVector((Vector6d() << 0, 0, 2, 0, 0, 25).finished(), EulerConvention::kXYZ);
  ASSERT_TRUE(SaveSessionConfig(dir, config).ok());
  StatusOr<SessionConfig> loaded = LoadSessionConfig(dir);
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  EXPECT_EQ(loaded->robot, "inria-left-hand");
  EXPECT_EQ(loaded->target, "aprilgrid-6x6");
  EXPECT_DOUBLE_EQ(loaded->noise.leg, 0.004);
  ASSERT_TRUE(loaded->base_from_camera.has_value());
  EXPECT_LT((loaded->base_from_camera->position - config.base_from_camera->position).norm(), 1e-12);
  EXPECT_LT(RotationDistance(loaded->platform_from_target->rotation, config.platform_from_target->rotation), 1e-12);
}

TEST(Session, ReadsLegsWithHoldout) {
  TempDir temp;
  const std::string dir = MakeSession(temp);
  WriteTextFile(dir + "/legs.csv",
                "image,L1,L2,L3,L4,L5,L6,holdout\n"
                "a.png,1,2,3,4,5,6,0\n"
                "# a comment\n"
                "b.png,0.5,0.5,0.5,0.5,0.5,0.5,1\n"
                "c.png,1,1,1,1,1,1,0\n");
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(dir);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 3u);
  EXPECT_EQ((*rows)[1].image, "b.png");
  EXPECT_TRUE((*rows)[1].holdout);
  EXPECT_FALSE((*rows)[0].holdout);
  EXPECT_DOUBLE_EQ((*rows)[0].legs[5], 6);
  EXPECT_EQ((*rows)[2].line, 5);
}

TEST(Session, LegsErrorsNameTheFileAndLine) {
  TempDir temp;
  const std::string dir = MakeSession(temp);
  const std::string header = "image,L1,L2,L3,L4,L5,L6\n";
  EXPECT_THAT(LegsError(dir, header + "a.png,1,2,3,4,5,6\nb.png,1,2,3,4,5,6\nd.png,1,2,3,4,5,6\n"),
              HasSubstr("legs.csv:4: image 'd.png' is not in images/"));
  EXPECT_THAT(LegsError(dir, header + "a.png,1,2,3,4,5,6\nb.png,1,2,3,4,5\n"),
              HasSubstr("legs.csv:3: 6 columns, header has 7"));
  EXPECT_THAT(LegsError(dir, header + "a.png,1,2,3,4,5,6\nb.png,1,2,3,4,5,6\n"), HasSubstr("c.png: no row in"));
  EXPECT_THAT(LegsError(dir, header + "a.png,1,2,3,4,5,6\na.png,1,2,3,4,5,6\n"),
              HasSubstr("legs.csv:3: image 'a.png' has a second row"));
  EXPECT_THAT(LegsError(dir, "image,L1,L2,L3,L4,L5,L6,holdout\na.png,1,2,3,4,5,6,2\n"),
              HasSubstr("legs.csv:2: column 'holdout': '2' is not 0 or 1"));
  // Missing readings say how to enter them.
  EXPECT_THAT(LegsError(dir, header + "a.png,1,2,3,4,5,6\nb.png,1,2,3,4,5,6\n"),
              HasSubstr("enter the six leg readings of each image"));
  std::filesystem::remove(dir + "/legs.csv");
  StatusOr<std::vector<LegsRow>> none = LoadSessionLegs(dir);
  ASSERT_FALSE(none.ok());
  EXPECT_THAT(none.status().message(), HasSubstr("legs.csv: no readings yet: enter the six leg readings"));
}

std::string ConfigError(const std::string& dir, const std::string& yaml) {
  WriteTextFile(dir + "/session.yaml", yaml);
  return testing::ErrorMessage(LoadSessionConfig(dir), yaml);
}

// Shapes fuzz/session_fuzz found throwing out of LoadSessionConfig.
TEST(Session, ConfigErrorsForMisshapenFramesAndNoise) {
  TempDir temp;
  const std::string dir = temp.File("s");
  ASSERT_TRUE(InitSession(dir, Config()).ok());
  const std::string head = "robot: r.yaml\ncamera: c.yaml\ntarget: t.yaml\n";
  EXPECT_THAT(ConfigError(dir, head + "frames:\n  base_from_camera: [0, 0, 50, 180, 0, 0]\n"),
              HasSubstr("session.yaml: frames.platform_from_target: missing"));
  EXPECT_THAT(ConfigError(dir, head + "frames: 3\n"), HasSubstr("session.yaml: frames: expected"));
  EXPECT_THAT(ConfigError(dir, head + "frames: [1, 2]\n"), HasSubstr("session.yaml: frames: expected"));
  EXPECT_THAT(ConfigError(dir, head + "noise: 0.1\n"), HasSubstr("session.yaml: noise: expected a mapping"));
}

}  // namespace
}  // namespace hexcal

// The calibrated robot file loads back as the calibrated robot, exactly, and
// its calibration section holds what produced it.
#include "core/calibration_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "core/candidates.h"
#include "core/robot_io.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

CalibrationResult CalibrateSample(int count, const std::string& robot = "inria-left-hand") {
  const Robot nominal = Preset(robot);
  ParameterVector truth = ParametersOf(nominal);
  for (int k = 0; k < kNumParams; ++k) truth[k] += Uniform(-0.3, 0.3);
  const Robot true_robot = WithParameters(nominal, truth);
  CandidateOptions candidates;
  candidates.count = count;
  const StatusOr<CandidateSet> poses = GenerateCandidates(nominal, candidates);
  EXPECT_TRUE(poses.ok()) << poses.status().message();
  std::vector<Measurement> measurements;
  for (const Vector6d& v : poses->poses) {
    Measurement m{v, InverseKinematics(true_robot, true_robot.PoseFromVector(v)), std::nullopt};
    m.legs += LegReadings::Constant(Uniform(-0.001, 0.001));
    measurements.push_back(m);
  }
  StatusOr<CalibrationResult> result = Calibrate(nominal, measurements);
  EXPECT_TRUE(result.ok()) << result.status().message();
  return *result;
}

TEST(CalibrationFile, LoadsBackAsTheCalibratedRobot) {
  TempDir dir;
  const CalibrationResult result = CalibrateSample(12);
  CalibrationInputs inputs{"inria-left-hand", "data/m: 1.csv", {}, "2026-11-22T10:00:00Z"};
  ASSERT_TRUE(SaveCalibratedRobot(dir.File("calibrated.yaml"), result, inputs).ok());
  StatusOr<Robot> loaded = LoadRobot(dir.File("calibrated.yaml"));
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  EXPECT_EQ(ParametersOf(*loaded), ParametersOf(result.robot));
  EXPECT_EQ(loaded->name, result.robot.name);
  EXPECT_TRUE(loaded->limits.pose_box.has_value());

  const YAML::Node calibration = YAML::LoadFile(dir.File("calibrated.yaml"))["calibration"];
  ASSERT_TRUE(calibration.IsMap());
  EXPECT_EQ(calibration["date"].as<std::string>(), "2026-11-22T10:00:00Z");
  EXPECT_EQ(calibration["nominal_robot"].as<std::string>(), "inria-left-hand");
  EXPECT_EQ(calibration["measurements"]["path"].as<std::string>(), "data/m: 1.csv");
  EXPECT_EQ(calibration["measurements"]["count"].as<int>(), 12);
  EXPECT_EQ(calibration["options"]["loss"].as<std::string>(), "none");
  EXPECT_FALSE(calibration["options"]["weighted"].as<bool>());
  EXPECT_EQ(calibration["length_unit"].as<std::string>(), "cm");
  ASSERT_EQ(calibration["legs"].size(), 6u);
  for (int i = 0; i < kNumLegs; ++i) {
    const YAML::Node leg = calibration["legs"][i];
    const LegCalibration& expected = result.legs[i];
    EXPECT_EQ(leg["sigma_a"][2].as<double>(), expected.std_dev[2]);
    EXPECT_EQ(leg["sigma_b"][0].as<double>(), expected.std_dev[3]);
    EXPECT_EQ(leg["sigma_l"].as<double>(), expected.std_dev[6]);
    EXPECT_EQ(leg["residual_rms"].as<double>(), expected.residual_rms);
    EXPECT_EQ(leg["termination"].as<std::string>(), "CONVERGENCE");
    EXPECT_EQ(leg["iterations"].as<int>(), expected.iterations);
  }
}

// The screening's options and each leg's excluded rows (1-based) are in the file.
TEST(CalibrationFile, NamesTheExcludedOutliers) {
  CalibrationResult result = CalibrateSample(12);
  result.legs[2].outliers = {{7, 1.0, 480, true}};
  CalibrationOptions options;
  options.outliers.enabled = true;
  const std::string text = CalibratedRobotToYaml(result, {"inria-left-hand", "m.csv", options, CurrentUtcTimestamp()});
  const YAML::Node calibration = YAML::Load(text)["calibration"];
  EXPECT_EQ(calibration["options"]["outliers"]["threshold"].as<double>(), 5);
  EXPECT_FALSE(calibration["options"]["outliers"]["keep"].as<bool>());
  EXPECT_EQ(calibration["legs"][2]["excluded_measurements"][0].as<int>(), 8);
  EXPECT_FALSE(calibration["legs"][1]["excluded_measurements"]);
  EXPECT_TRUE(ParseRobotYaml(text, "calibrated.yaml").ok());
}

TEST(CalibrationFile, SevenMeasurementsWriteNoSigma) {
  const CalibrationResult result = CalibrateSample(7);
  const std::string text = CalibratedRobotToYaml(result, {"inria-left-hand", "m.csv", {}, CurrentUtcTimestamp()});
  EXPECT_THAT(text, HasSubstr("sigma_a: null, sigma_b: null, sigma_l: null"));
  EXPECT_TRUE(ParseRobotYaml(text, "calibrated.yaml").ok());
}

TEST(CalibrationFile, TimestampIsIsoUtc) {
  const std::string now = CurrentUtcTimestamp();
  ASSERT_EQ(now.size(), 20u);
  EXPECT_EQ(now[4], '-');
  EXPECT_EQ(now[10], 'T');
  EXPECT_EQ(now.back(), 'Z');
}

}  // namespace
}  // namespace hexcal

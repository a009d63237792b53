// Validation by forward kinematics: the true robot explains exact measurements
// to round-off, a wrong robot does not, and rows whose readings no pose can
// reach are counted, not dropped silently.
#include "core/validation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/candidates.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

std::vector<Measurement> ExactMeasurements(const Robot& truth, int count) {
  CandidateOptions candidates;
  candidates.count = count;
  candidates.seed = 21;
  const StatusOr<CandidateSet> poses = GenerateCandidates(truth, candidates);
  EXPECT_TRUE(poses.ok()) << poses.status().message();
  std::vector<Measurement> measurements;
  for (const Vector6d& v : poses->poses) {
    measurements.push_back({v, InverseKinematics(truth, truth.PoseFromVector(v)), std::nullopt});
  }
  return measurements;
}

Robot Perturbed(const Robot& nominal, double half_width) {
  ParameterVector p = ParametersOf(nominal);
  for (int k = 0; k < kNumParams; ++k) p[k] += Uniform(-half_width, half_width);
  return WithParameters(nominal, p);
}

TEST(Validation, TheTrueRobotHasNoErrorAndTheNominalOneHasLarge) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = Perturbed(nominal, 0.5);
  const std::vector<Measurement> measurements = ExactMeasurements(nominal, 20);
  std::vector<Measurement> of_truth;
  for (const Measurement& m : measurements)
    of_truth.push_back({m.pose, InverseKinematics(truth, truth.PoseFromVector(m.pose)), std::nullopt});

  StatusOr<ValidationReport> exact = Validate(truth, of_truth);
  ASSERT_TRUE(exact.ok()) << exact.status().message();
  EXPECT_EQ(exact->failed, 0);
  EXPECT_EQ(exact->position.count, 20);
  EXPECT_LT(exact->position.max, 1e-9);
  EXPECT_LT(exact->orientation_deg.max, 1e-8);

  StatusOr<ValidationReport> wrong = Validate(nominal, of_truth);
  ASSERT_TRUE(wrong.ok()) << wrong.status().message();
  EXPECT_GT(wrong->position.mean, 0.05);  // cm: parameters off by up to 0.5 cm
  EXPECT_GT(wrong->orientation_deg.mean, 0.05);
  EXPECT_GE(wrong->position.max, wrong->position.rms);
  EXPECT_GE(wrong->position.rms, wrong->position.mean);
}

TEST(Validation, StatisticsAreThoseOfTheRows) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = Perturbed(nominal, 0.2);
  std::vector<Measurement> measurements;
  for (const Measurement& m : ExactMeasurements(nominal, 6)) {
    measurements.push_back({m.pose, InverseKinematics(truth, truth.PoseFromVector(m.pose)), std::nullopt});
  }
  StatusOr<ValidationReport> report = Validate(nominal, measurements);
  ASSERT_TRUE(report.ok());
  double sum = 0, max = 0;
  for (const ValidationRow& row : report->rows) {
    ASSERT_TRUE(row.ok);
    sum += row.position_error;
    max = std::max(max, row.position_error);
  }
  EXPECT_DOUBLE_EQ(report->position.mean, sum / 6);
  EXPECT_EQ(report->position.max, max);
}

TEST(Validation, UnreachableReadingsAreCountedAsFailures) {
  const Robot nominal = Preset("inria-left-hand");
  std::vector<Measurement> measurements = ExactMeasurements(nominal, 5);
  measurements[2].legs << 100, -60, 100, -60, 100, -60;  // no pose has these leg lengths
  StatusOr<ValidationReport> report = Validate(nominal, measurements);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->failed, 1);
  EXPECT_FALSE(report->rows[2].ok);
  EXPECT_THAT(report->rows[2].error, HasSubstr("did not converge"));
  EXPECT_EQ(report->position.count, 4);

  std::vector<Measurement> all_bad(2, measurements[2]);
  StatusOr<ValidationReport> none = Validate(nominal, all_bad);
  ASSERT_FALSE(none.ok());
  EXPECT_THAT(none.status().message(), HasSubstr("failed for all 2 measurements"));
  EXPECT_FALSE(Validate(nominal, {}).ok());
}

}  // namespace
}  // namespace hexcal

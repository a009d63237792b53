// Outlier screening of the per-leg fits (core/outlier_screening.h) against an
// independent truth made here: a perturbed robot, its IK readings at random
// poses with uniform noise, and one reading moved by 1 cm. The bad row must be
// named and left out, the parameters must be as good as without that row, and
// clean data must raise no alarm.
#include "core/outlier_screening.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/calibration.h"
#include "core/inverse_kinematics.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::PerturbedRobot;
using ::hexcal::testing::Preset;
using ::hexcal::testing::RandomFeasiblePoses;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

constexpr NoiseModel kNoise{0.001, 0.01, 0.001};  // the paper's half-widths (cm, degrees, cm)
constexpr int kBadRow = 7, kBadLeg = 2;           // legs.csv line 9, leg 3

// Readings of `truth` at `poses` with uniform noise of `scale` times kNoise.
std::vector<Measurement> Measure(const Robot& truth, const std::vector<Vector6d>& poses, double scale = 1) {
  std::vector<Measurement> measurements;
  for (const Vector6d& v : poses) {
    Measurement m;
    m.legs = InverseKinematics(truth, truth.PoseFromVector(v));
    m.pose = v;
    for (int k = 0; k < 6; ++k) m.pose[k] += scale * Uniform(-1, 1) * (k < 3 ? kNoise.position : kNoise.angle_deg);
    for (int i = 0; i < kNumLegs; ++i) m.legs[i] += scale * Uniform(-1, 1) * kNoise.leg;
    measurements.push_back(m);
  }
  return measurements;
}

CalibrationOptions Screening(bool keep = false) {
  CalibrationOptions options;
  options.weighted = true;
  options.noise = kNoise;
  options.outliers.enabled = true;
  options.outliers.keep = keep;
  return options;
}

CalibrationResult CalibrateOk(const Robot& nominal, const std::vector<Measurement>& measurements,
                              const CalibrationOptions& options) {
  StatusOr<CalibrationResult> result = Calibrate(nominal, measurements, options);
  EXPECT_TRUE(result.ok()) << result.status().message();
  return result.ok() ? *result : CalibrationResult{};
}

double MeanError(const CalibrationResult& result, const Robot& truth) {
  return (result.Estimates() - ParametersOf(truth)).cwiseAbs().mean();
}

int CountOutliers(const CalibrationResult& result) {
  int count = 0;
  for (const LegCalibration& leg : result.legs) count += static_cast<int>(leg.outliers.size());
  return count;
}

TEST(FlagOutliers, RobustScatterIsTheGaussianScaleAndRaisesTheBar) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gaussian;
  std::vector<double> z(4000);
  for (double& value : z) value = 2 * gaussian(rng);
  EXPECT_NEAR(RobustScatter(z, 7), 2, 0.1);
  EXPECT_EQ(RobustScatter({}, 7), 0);
  // Scatter ŝ ≈ 1.6 here (14 values, 7 parameters): only the far value is over 5 ŝ.
  // Ten times the scatter moves the bar ten times: 120 is still over, 40 is not.
  std::vector<double> unit = {0.3, -1.1, 0.8, -0.2, 1.4, -0.6, 0.1, 0.9, -1.3, 0.5, 0.7, -0.4, 12, -0.9};
  EXPECT_EQ(FlagOutliers(unit, 7, 5), std::vector<int>{12});
  for (double& value : unit) value *= 10;
  EXPECT_EQ(FlagOutliers(unit, 7, 5), std::vector<int>{12});
  unit[12] = 40;
  EXPECT_TRUE(FlagOutliers(unit, 7, 5).empty());
}

TEST(OutlierScreening, AReadingOffByOneCentimetreIsNamedAndLeftOut) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  const std::vector<Measurement> clean = Measure(truth, RandomFeasiblePoses(nominal, 24, 11));
  std::vector<Measurement> bad = clean;
  bad[kBadRow].legs[kBadLeg] += 1.0;
  std::vector<Measurement> without = clean;
  without.erase(without.begin() + kBadRow);

  const CalibrationResult screened = CalibrateOk(nominal, bad, Screening());
  ASSERT_EQ(CountOutliers(screened), 1);
  const std::vector<RowOutlier>& outliers = screened.legs[kBadLeg].outliers;
  ASSERT_EQ(outliers.size(), 1u);
  EXPECT_EQ(outliers[0].measurement, kBadRow);
  EXPECT_NEAR(outliers[0].residual, 1.0, 0.01);
  EXPECT_GT(outliers[0].z, 100);
  EXPECT_TRUE(outliers[0].excluded);
  EXPECT_EQ(screened.legs[kBadLeg].rows_used, 23);

  // Leg 3 is exactly the weighted fit without the row; the whole robot as good as that fit.
  CalibrationOptions plain = Screening();
  plain.outliers.enabled = false;
  const CalibrationResult reference = CalibrateOk(nominal, without, plain);
  EXPECT_TRUE(MatrixNear(screened.legs[kBadLeg].estimate, reference.legs[kBadLeg].estimate, 1e-9));
  EXPECT_TRUE(MatrixNear(screened.legs[kBadLeg].std_dev, reference.legs[kBadLeg].std_dev, 1e-9));
  const double screened_error = MeanError(screened, truth), reference_error = MeanError(reference, truth);
  EXPECT_LT(screened_error, 1.2 * reference_error) << screened_error << " against " << reference_error;
  // Unscreened, the bad row bends leg 3 far beyond that (and takes more than
  // the default 100 iterations to do so: plain least squares fails here).
  EXPECT_FALSE(Calibrate(nominal, bad, plain).ok());
  plain.max_iterations = 2000;
  const double bent_error = MeanError(CalibrateOk(nominal, bad, plain), truth);
  EXPECT_GT(bent_error, 20 * reference_error) << bent_error << " against " << reference_error;
}

TEST(OutlierScreening, KeptOutliersAreNamedAndStayInTheFit) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  std::vector<Measurement> bad = Measure(truth, RandomFeasiblePoses(nominal, 24, 12));
  bad[kBadRow].legs[kBadLeg] -= 1.0;
  const CalibrationResult kept = CalibrateOk(nominal, bad, Screening(/*keep=*/true));
  const std::vector<RowOutlier>& outliers = kept.legs[kBadLeg].outliers;
  ASSERT_EQ(outliers.size(), 1u);
  EXPECT_EQ(outliers[0].measurement, kBadRow);
  EXPECT_NEAR(outliers[0].residual, -1.0, 0.01);
  EXPECT_LT(outliers[0].z, -100);
  EXPECT_FALSE(outliers[0].excluded);
  EXPECT_EQ(kept.legs[kBadLeg].rows_used, 24);
  CalibrationOptions plain = Screening();
  plain.outliers.enabled = false;
  EXPECT_TRUE(MatrixNear(kept.Estimates(), CalibrateOk(nominal, bad, plain).Estimates(), 1e-12));
}

// Five robots, pose sets and noise draws, 24 and 60 poses: 504 tests each, none flagged.
TEST(OutlierScreening, CleanDataRaiseNoAlarm) {
  const Robot nominal = Preset("inria-left-hand");
  for (int seed = 1; seed <= 5; ++seed) {
    const Robot truth = PerturbedRobot(nominal, 0.5);
    for (int poses : {24, 60}) {
      const CalibrationResult result =
          CalibrateOk(nominal, Measure(truth, RandomFeasiblePoses(nominal, poses, 100 + seed)), Screening());
      EXPECT_EQ(CountOutliers(result), 0) << "seed " << seed << ", " << poses << " poses";
    }
  }
}

// Noise ten times the model's: ŝ ≈ 10 raises the bar instead of flagging every row.
TEST(OutlierScreening, AnOptimisticNoiseModelDoesNotFlagEveryRow) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  std::vector<Measurement> noisy = Measure(truth, RandomFeasiblePoses(nominal, 30, 13), 10);
  EXPECT_EQ(CountOutliers(CalibrateOk(nominal, noisy, Screening())), 0);
  noisy[kBadRow].legs[kBadLeg] += 1.0;  // still ~100 of the observed σ
  const CalibrationResult result = CalibrateOk(nominal, noisy, Screening());
  ASSERT_EQ(CountOutliers(result), 1);
  EXPECT_EQ(result.legs[kBadLeg].outliers[0].measurement, kBadRow);
}

// Below kMinRowsToScreen rows the robust fit could explain any one row away.
TEST(OutlierScreening, TooFewRowsAreNotScreened) {
  const Robot nominal = Preset("inria-left-hand");
  const Robot truth = PerturbedRobot(nominal, 0.5);
  std::vector<Measurement> few = Measure(truth, RandomFeasiblePoses(nominal, kMinRowsToScreen - 1, 14));
  few[3].legs[0] += 1.0;
  const CalibrationResult result = CalibrateOk(nominal, few, Screening());
  EXPECT_EQ(CountOutliers(result), 0);
  EXPECT_EQ(result.legs[0].rows_used, kMinRowsToScreen - 1);
}

TEST(OutlierScreening, OptionsAreChecked) {
  std::string error;
  CalibrationOptions options = Screening();
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.outliers.threshold = 2;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_THAT(error, HasSubstr("outlier threshold must be between 3 and 100 standard deviations, got 2"));
  options = Screening();
  options.weighted = false;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_THAT(error, HasSubstr("outlier screening needs weighted residuals"));
  options = Screening();
  options.loss = RobustLoss::kHuber;
  EXPECT_FALSE(options.IsValid(&error));
  const OptionSpec<OutlierScreening>* threshold = FindOption(OutlierScreeningOptions(), "outlier_threshold");
  ASSERT_NE(threshold, nullptr);
  OutlierScreening screening;
  EXPECT_THAT(ApplyOptionText(*threshold, "101", &screening, "--outlier-threshold").message(),
              HasSubstr("--outlier-threshold: must be at most 100 sigma, got 101"));
}

}  // namespace
}  // namespace hexcal

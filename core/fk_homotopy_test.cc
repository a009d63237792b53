// The Study-parameter system and forward kinematics with every assembly mode,
// against independent truths: the leg equations evaluated directly, complex
// finite differences, poses whose readings come from inverse kinematics, and
// Dietmaier's platform with 40 real assembly modes.
#include "core/fk_homotopy.h"

#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/candidates.h"
#include "core/constraints.h"
#include "core/forward_kinematics.h"
#include "core/robot_io.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::SourceDir;
using ::hexcal::testing::Uniform;

std::array<LegCoefficients, 6> Coefficients(const StudyParameters& p) {
  std::array<LegCoefficients, 6> c;
  for (int i = 0; i < 6; ++i) c[i] = CoefficientsOf(p.a[i], p.b[i], p.d2[i]);
  return c;
}

CVector8 Evaluate(const std::array<LegCoefficients, 6>& legs, const CVector8& chart, const CVector8& z) {
  CVector8 f;
  EvaluateStudySystem(legs, chart, z, &f, nullptr);
  return f;
}

Complex RandomComplex() { return Complex(Uniform(-1, 1), Uniform(-1, 1)); }
CVector3 RandomCVector3() { return CVector3(RandomComplex(), RandomComplex(), RandomComplex()); }
Eigen::Vector3d RandomVector3(double lo, double hi) {
  return Eigen::Vector3d(Uniform(lo, hi), Uniform(lo, hi), Uniform(lo, hi));
}

// A robot in metres with zero offsets, so readings are the leg lengths.
Robot MakeRobot(const std::array<Eigen::Vector3d, 6>& a, const std::array<Eigen::Vector3d, 6>& b) {
  Robot robot;
  robot.name = "test-platform";
  robot.length_unit = LengthUnit::kMetre;
  for (int i = 0; i < kNumLegs; ++i) robot.legs[i] = Leg{a[i], b[i], 0.0, 0.0, 10.0};
  return robot;
}

bool ContainsPose(const std::vector<Pose>& poses, const Pose& truth, double tolerance) {
  return std::any_of(poses.begin(), poses.end(), [&](const Pose& p) {
    return (p.position - truth.position).norm() < tolerance && RotationDistance(p.rotation, truth.rotation) < tolerance;
  });
}

double WorstLegError(const Robot& robot, const std::vector<Pose>& poses, const LegReadings& readings) {
  double worst = 0;
  for (const Pose& p : poses) {
    worst = std::max(worst, (InverseKinematics(robot, p) - readings).cwiseAbs().maxCoeff());
  }
  return worst;
}

// The generic start system has 40 distinct solutions, each a root of its own system.
TEST(StudySystem, GenericStartSystemHas40DistinctRoots) {
  const StartSystem& start = GenericStartSystem();
  ASSERT_EQ(start.solutions.size(), 40u);
  const std::array<LegCoefficients, 6> legs = Coefficients(start.params);
  for (size_t k = 0; k < start.solutions.size(); ++k) {
    const CVector8& z = start.solutions[k];
    EXPECT_LT(Evaluate(legs, start.chart, z).norm(), 1e-10) << "solution " << k;
    const Complex delta = z.head<4>().transpose() * z.head<4>();
    EXPECT_GT(std::abs(delta), 1e-6) << "solution " << k << " lies on the exceptional quadric";
    for (size_t m = 0; m < k; ++m) {
      EXPECT_GT((z - start.solutions[m]).norm(), 1e-4 * (1 + z.norm())) << k << " vs " << m;
    }
  }
}

// The shipped start solutions are the instance's own: each a root found by a
// fresh 128-path solve, none missing, and the process uses them.
TEST(StudySystem, ShippedStartSolutionsAreTheSolvedOnes) {
  const StartSystem shipped = ShippedStartSystem();
  const StartSystem solved = SolveGenericInstance(kStartSystemSeed);
  ASSERT_EQ(solved.solutions.size(), 40u);
  ASSERT_EQ(shipped.solutions.size(), 40u) << "regenerate core/fk_start_solutions.inc as:\n"
                                           << FormatStartSolutions(solved.solutions);
  for (const CVector8& z : solved.solutions) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const CVector8& other : shipped.solutions) nearest = std::min(nearest, (z - other).norm());
    EXPECT_LT(nearest, 1e-10 * (1 + z.norm()));
  }
  EXPECT_TRUE(GenericStartSystem().from_shipped_data);
  EXPECT_EQ(GenericStartSystem().total_degree_runs, 0);
}

// StudyFromPose then StudyToComplexPose gives back R and t, real, and the Study quadric holds.
TEST(StudySystem, StudyPoseRoundTrip) {
  for (int trial = 0; trial < 200; ++trial) {
    Pose pose;
    pose.position = RandomVector3(-5, 5);
    // Angles up to 180° so that e0 < 0 before normalisation also occurs.
    pose.rotation = Eigen::AngleAxisd(Uniform(0, kPi), RandomVector3(-1, 1).normalized()).matrix();
    const CVector8 z = StudyFromPose(pose);
    EXPECT_NEAR(z.imag().norm(), 0.0, 0.0);
    EXPECT_GE(z[0].real(), 0.0);
    EXPECT_NEAR(z.real().head<4>().norm(), 1.0, 1e-14);
    EXPECT_NEAR(std::abs(Complex(z.head<4>().transpose() * z.tail<4>())), 0.0, 1e-14);
    CMatrix3 rotation;
    CVector3 translation;
    StudyToComplexPose(z, &rotation, &translation);
    EXPECT_TRUE(MatrixNear(rotation.real(), pose.rotation, 1e-14));
    EXPECT_TRUE(MatrixNear(translation.real(), pose.position, 1e-13));
    EXPECT_EQ(rotation.imag().norm() + translation.imag().norm(), 0.0);
    // The representation is projective: a complex multiple is the same pose.
    StudyToComplexPose(Complex(0.3, -1.7) * z, &rotation, &translation);
    EXPECT_TRUE(MatrixNear(rotation.real(), pose.rotation, 1e-13));
    EXPECT_TRUE(MatrixNear(translation.real(), pose.position, 1e-12));
    EXPECT_LT(rotation.imag().norm() + translation.imag().norm(), 1e-12);
  }
}

// dF/dz against central differences along real and imaginary directions: F is
// holomorphic, so both give the same complex derivative.
TEST(StudySystem, JacobianMatchesComplexFiniteDifferences) {
  for (int trial = 0; trial < 20; ++trial) {
    std::array<LegCoefficients, 6> legs;
    for (int i = 0; i < 6; ++i) legs[i] = CoefficientsOf(RandomCVector3(), RandomCVector3(), RandomComplex());
    CVector8 chart, z;
    for (int k = 0; k < 8; ++k) chart[k] = RandomComplex(), z[k] = RandomComplex();
    CVector8 f;
    CMatrix8 jacobian;
    EvaluateStudySystem(legs, chart, z, &f, &jacobian);
    EXPECT_TRUE(MatrixNear(f, Evaluate(legs, chart, z), 1e-12)) << (f - Evaluate(legs, chart, z)).transpose();
    const double h = 1e-6;
    for (int k = 0; k < 8; ++k) {
      for (const Complex direction : {Complex(1, 0), Complex(0, 1)}) {
        const CVector8 dz = CVector8::Unit(k) * (h * direction);
        const CVector8 numeric =
            (Evaluate(legs, chart, z + dz) - Evaluate(legs, chart, z - dz)) / (2.0 * h * direction);
        EXPECT_LT((jacobian.col(k) - numeric).norm(), 1e-8) << "column " << k << " direction " << direction;
      }
    }
  }
}

// At a real pose with e·e = 1, leg equation i is |R b_i + t - a_i|² - d_i² (any d_i), the
// Study quadric vanishes, and the leg equations are homogeneous of degree 2 in z.
TEST(StudySystem, LegEquationsAtARealPose) {
  for (int trial = 0; trial < 50; ++trial) {
    Pose pose;
    pose.position = RandomVector3(-1, 1);
    pose.rotation = Eigen::AngleAxisd(Uniform(0, 3), RandomVector3(-1, 1).normalized()).matrix();
    std::array<LegCoefficients, 6> legs, exact_legs;
    Eigen::Matrix<double, 6, 1> squared_length, d2;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d a = RandomVector3(-1, 1), b = RandomVector3(-1, 1);
      squared_length[i] = (pose.rotation * b + pose.position - a).squaredNorm();
      d2[i] = Uniform(0, 3);
      legs[i] = CoefficientsOf(a.cast<Complex>(), b.cast<Complex>(), d2[i]);
      exact_legs[i] = CoefficientsOf(a.cast<Complex>(), b.cast<Complex>(), squared_length[i]);
    }
    const CVector8 z = StudyFromPose(pose), chart = CVector8::Zero();
    const CVector8 f = Evaluate(legs, chart, z), f_exact = Evaluate(exact_legs, chart, z);
    const Complex lambda(0.7, 0.4);
    const CVector8 f_scaled = Evaluate(legs, chart, lambda * z);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(std::abs(f_exact[i]), 0.0, 1e-13) << "leg " << i;
      EXPECT_NEAR(std::abs(f[i] - (squared_length[i] - d2[i])), 0.0, 1e-13) << "leg " << i;
      EXPECT_NEAR(std::abs(f_scaled[i] - lambda * lambda * f[i]), 0.0, 1e-13) << "leg " << i;
    }
    EXPECT_NEAR(std::abs(f[6]), 0.0, 1e-15);
  }
}

// Random non-planar platforms: the true pose is among the real modes, every mode
// satisfies the readings, and the 40 paths all end at finite solutions.
TEST(ForwardKinematicsAll, RandomGeneralPlatforms) {
  const auto begin = std::chrono::steady_clock::now();
  for (int trial = 0; trial < 30; ++trial) {
    std::array<Eigen::Vector3d, 6> a, b;
    for (int i = 0; i < 6; ++i) a[i] = RandomVector3(-1, 1), b[i] = RandomVector3(-0.6, 0.6);
    const Robot robot = MakeRobot(a, b);
    Pose truth;
    truth.position = Eigen::Vector3d(Uniform(-0.3, 0.3), Uniform(-0.3, 0.3), Uniform(1, 1.5));
    truth.rotation = RotationFromEuler(RandomVector3(-0.5, 0.5), EulerConvention::kXYZ);
    const LegReadings readings = InverseKinematics(robot, truth);
    StatusOr<FkAllResult> fk = ForwardKinematicsAll(robot, readings);
    ASSERT_TRUE(fk.ok()) << fk.status().message();
    EXPECT_TRUE(ContainsPose(fk->poses, truth, 1e-8)) << "trial " << trial;
    EXPECT_LT(WorstLegError(robot, fk->poses, readings), 1e-9) << "trial " << trial;
    EXPECT_EQ(fk->failed_paths, 0) << "trial " << trial;
    EXPECT_EQ(fk->tracked_paths, 40);
    EXPECT_EQ(static_cast<int>(fk->poses.size()) + fk->complex_solutions, 40) << "trial " << trial;
    // The target system is real, so its non-real roots come in conjugate pairs.
    EXPECT_EQ(fk->complex_solutions % 2, 0) << "trial " << trial;
  }
  std::cout << "[ timing   ] 30 random platforms: "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() << " s\n";
}

// INRIA preset at reachable poses: the true pose is found, and every mode satisfies IK.
TEST(ForwardKinematicsAll, InriaPresetFindsTruePose) {
  const Robot robot = *LoadRobot("inria-left-hand");
  for (int trial = 0; trial < 10; ++trial) {
    Vector6d v;
    v << Uniform(-2, 2), Uniform(-2, 2), Uniform(52.5, 54.5), Uniform(-5, 5), Uniform(-5, 5), Uniform(-5, 5);
    const Pose truth = robot.PoseFromVector(v);
    const LegReadings readings = InverseKinematics(robot, truth);
    StatusOr<FkAllResult> fk = ForwardKinematicsAll(robot, readings);
    ASSERT_TRUE(fk.ok()) << fk.status().message();
    EXPECT_TRUE(ContainsPose(fk->poses, truth, 1e-8)) << v.transpose();
    EXPECT_LT(WorstLegError(robot, fk->poses, readings), 1e-9);
  }
}

// Issue 13: at z = 52, q3 = 90° the INRIA robot is at a parallel singularity;
// the true pose and a neighbouring mode merge into a double root, the paths to
// it stop short, and the homotopy alone answered "0 real assembly modes". The
// end-game recovers the true pose and flags it.
TEST(ForwardKinematicsAll, SingularReadingsGiveTheRealPoseFlagged) {
  const Robot robot = *LoadRobot("inria-left-hand");
  Vector6d v;
  v << 0, 0, 52, 0, 0, 90;
  const Pose truth = robot.PoseFromVector(v);
  const LegReadings readings = InverseKinematics(robot, truth);
  StatusOr<FkAllResult> fk = ForwardKinematicsAll(robot, readings);
  ASSERT_TRUE(fk.ok()) << fk.status().message();
  ASSERT_FALSE(fk->poses.empty());
  EXPECT_TRUE(ContainsPose(fk->poses, truth, 1e-5));
  EXPECT_LT(WorstLegError(robot, fk->poses, readings), 1e-9);
  ASSERT_EQ(fk->at_singularity.size(), fk->poses.size());
  EXPECT_GE(fk->SingularCount(), 1);
  EXPECT_GE(fk->endgame_poses, 1);
}

// Just off the singularity the modes are distinct and regular: none is flagged.
TEST(ForwardKinematicsAll, ReadingsOffTheSingularityAreNotFlagged) {
  const Robot robot = *LoadRobot("inria-left-hand");
  Vector6d v;
  v << 0, 0, 52, 0, 0, 80;
  const Pose truth = robot.PoseFromVector(v);
  StatusOr<FkAllResult> fk = ForwardKinematicsAll(robot, InverseKinematics(robot, truth));
  ASSERT_TRUE(fk.ok()) << fk.status().message();
  EXPECT_TRUE(ContainsPose(fk->poses, truth, 1e-8));
  EXPECT_EQ(fk->SingularCount(), 0);
}

// Reflection through the base plane z = 0: for a robot whose a_i and b_i all have z = 0,
// (D P, D R D) with D = diag(1, 1, -1) gives the same leg lengths as (P, R).
Pose Mirrored(const Pose& pose) {
  const Eigen::Matrix3d d = Eigen::Vector3d(1, 1, -1).asDiagonal();
  Pose mirrored;
  mirrored.position = d * pose.position;
  mirrored.rotation = d * pose.rotation * d;
  return mirrored;
}

// ForwardKinematicsAll at every stroke corner of the INRIA robot, solved once
// for the two tests that check it (the slowest part of this binary under ASan).
const std::vector<StatusOr<FkAllResult>>& InriaCornerModes() {
  static const std::vector<StatusOr<FkAllResult>> modes = [] {
    const Robot robot = *LoadRobot("inria-left-hand");
    std::vector<StatusOr<FkAllResult>> all;
    for (int corner = 0; corner < 64; ++corner) {
      all.push_back(ForwardKinematicsAll(robot, StrokeCornerReadings(robot, corner)));
    }
    return all;
  }();
  return modes;
}

// Every stroke corner of the INRIA robot (each L_i at its min or max): every mode satisfies
// the readings, comes with its mirror image (base and platform are planar), and includes every
// pose a multistart local FK finds. All-min and all-max are vertical lifts, so they have a mode.
// Some corners have no real mode at all (e.g. 5: L1 = L3 = 3.5, others 0); the multistart agrees.
TEST(ForwardKinematicsAll, InriaStrokeCorners) {
  const Robot robot = *LoadRobot("inria-left-hand");
  const auto begin = std::chrono::steady_clock::now();
  std::ostringstream summary;
  int total_real = 0, total_feasible = 0, corners_without_mode = 0;
  for (int corner = 0; corner < 64; ++corner) {
    const LegReadings readings = StrokeCornerReadings(robot, corner);
    const StatusOr<FkAllResult>& fk = InriaCornerModes()[corner];
    ASSERT_TRUE(fk.ok()) << fk.status().message();
    const std::vector<Pose>& modes = fk->poses;
    if (corner == 0 || corner == 63) {
      EXPECT_GE(modes.size(), 1u) << "corner " << corner;
    }
    EXPECT_LT(WorstLegError(robot, modes, readings), 1e-9) << "corner " << corner;
    EXPECT_EQ(static_cast<int>(modes.size()) + fk->complex_solutions + fk->failed_paths, 40);
    for (const Pose& mode : modes) EXPECT_TRUE(ContainsPose(modes, Mirrored(mode), 1e-7)) << "corner " << corner;
    for (int start = 0; start < 100; ++start) {
      Vector6d v;
      v << Uniform(-15, 15), Uniform(-15, 15), Uniform(40, 60), Uniform(-60, 60), Uniform(-40, 40), Uniform(-180, 180);
      StatusOr<LocalFkResult> local = ForwardKinematicsLocal(robot, readings, robot.PoseFromVector(v));
      if (local.ok()) {
        EXPECT_TRUE(ContainsPose(modes, local->pose, 1e-7)) << "corner " << corner << " missed mode";
      }
    }
    const int feasible = static_cast<int>(
        std::count_if(modes.begin(), modes.end(), [&](const Pose& p) { return IsFeasible(robot, p); }));
    summary << " " << corner << ":" << modes.size() << "/" << feasible;
    total_real += static_cast<int>(modes.size());
    total_feasible += feasible;
    corners_without_mode += modes.empty();
  }
  std::cout << "[ corners  ] corner:real/feasible" << summary.str() << "\n[ corners  ] total real " << total_real
            << ", feasible " << total_feasible << ", corners without a real mode " << corners_without_mode << ", "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() << " s\n";
  RecordProperty("real_modes", total_real);
  RecordProperty("feasible_modes", total_feasible);
}

// Dietmaier (ARK 1998): a 6-6 platform with 40 real assembly modes.
constexpr double kDietmaierLengths[6] = {1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071};

Robot DietmaierRobot() {
  return MakeRobot({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.107915, 0, 0), Eigen::Vector3d(0.549094, 0.756063, 0),
                    Eigen::Vector3d(0.735077, -0.223935, 0.525991), Eigen::Vector3d(0.514188, -0.526063, -0.368418),
                    Eigen::Vector3d(0.590473, 0.094733, -0.205018)},
                   {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.542805, 0, 0), Eigen::Vector3d(0.956919, -0.528915, 0),
                    Eigen::Vector3d(0.665885, -0.353482, 1.402538), Eigen::Vector3d(0.478359, 1.158742, 0.107672),
                    Eigen::Vector3d(-0.137087, -0.235121, 0.353913)});
}

::testing::AssertionResult HasFortyRealModes(const Robot& robot, const LegReadings& readings) {
  StatusOr<FkAllResult> fk = ForwardKinematicsAll(robot, readings);
  if (!fk.ok()) return ::testing::AssertionFailure() << fk.status().message();
  const double error = WorstLegError(robot, fk->poses, readings);
  if (fk->poses.size() != 40 || fk->complex_solutions != 0 || fk->failed_paths != 0 || !(error < 1e-9)) {
    return ::testing::AssertionFailure() << fk->poses.size() << " real, " << fk->complex_solutions << " complex, "
                                         << fk->failed_paths << " failed, worst leg error " << error;
  }
  return ::testing::AssertionSuccess();
}

TEST(ForwardKinematicsAll, DietmaierFortyRealModes) {
  const LegReadings readings = Eigen::Map<const LegReadings>(kDietmaierLengths);
  EXPECT_TRUE(HasFortyRealModes(DietmaierRobot(), readings));
}

// The same platform through the robot file, with the readings from its "# readings:" line.
TEST(ForwardKinematicsAll, DietmaierRobotFile) {
  const std::string path = (SourceDir() / "tests/data/dietmaier-40-real.yaml").string();
  StatusOr<Robot> robot = LoadRobot(path);
  ASSERT_TRUE(robot.ok()) << robot.status().message();
  EXPECT_EQ(robot->length_unit, LengthUnit::kMetre);
  for (int i = 0; i < kNumLegs; ++i) {
    EXPECT_EQ(robot->legs[i].a_in_base, DietmaierRobot().legs[i].a_in_base) << i;
    EXPECT_EQ(robot->legs[i].b_in_platform, DietmaierRobot().legs[i].b_in_platform) << i;
  }
  std::ifstream file(path);
  std::string line;
  LegReadings readings = LegReadings::Constant(std::nan(""));
  while (std::getline(file, line)) {
    if (line.rfind("# readings:", 0) != 0) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream numbers(line.substr(11));
    for (int i = 0; i < kNumLegs; ++i) numbers >> readings[i];
  }
  ASSERT_TRUE(readings.allFinite()) << "no '# readings:' line with six numbers in " << path;
  EXPECT_TRUE(MatrixNear(readings, Eigen::Map<const LegReadings>(kDietmaierLengths), 0.0));
  EXPECT_TRUE(HasFortyRealModes(*robot, readings));
}

}  // namespace
}  // namespace hexcal

namespace hexcal {
namespace {

::testing::AssertionResult SameModes(const FkAllResult& family, const FkAllResult& direct) {
  if (family.poses.size() != direct.poses.size() || family.SingularCount() != direct.SingularCount()) {
    return ::testing::AssertionFailure() << family.poses.size() << " modes (" << family.SingularCount()
                                         << " singular) from the family, " << direct.poses.size() << " ("
                                         << direct.SingularCount() << ") from the generic start";
  }
  for (const Pose& pose : direct.poses) {
    if (!ContainsPose(family.poses, pose, 1e-9)) {
      return ::testing::AssertionFailure() << "the family misses the mode at " << pose.position.transpose();
    }
  }
  return ::testing::AssertionSuccess();
}

// One hub and short homotopies in the leg lengths find exactly the modes the
// generic start finds, on every stroke corner of both presets (the boundary
// candidates) and at readings inside the strokes.
TEST(FkFamily, SameModesAsTheGenericStart) {
  for (const char* name : {"inria-left-hand", "deltalab-table"}) {
    const Robot robot = *LoadRobot(name);
    StatusOr<FkFamily> family = FkFamily::ForRobot(robot);
    ASSERT_TRUE(family.ok()) << family.status().message();
    EXPECT_LE(family->hub_solutions(), 40) << name;
    const bool inria = robot.name == "inria-left-hand";
    for (int corner = 0; corner < 64 + 8; ++corner) {
      LegReadings readings = StrokeCornerReadings(robot, corner % 64);
      if (corner >= 64) {
        for (int i = 0; i < kNumLegs; ++i) readings[i] = Uniform(robot.legs[i].stroke_min, robot.legs[i].stroke_max);
      }
      StatusOr<FkAllResult> via_family = family->Solve(readings);
      StatusOr<FkAllResult> direct =
          inria && corner < 64 ? InriaCornerModes()[corner] : ForwardKinematicsAll(robot, readings);
      ASSERT_TRUE(via_family.ok() && direct.ok());
      EXPECT_TRUE(SameModes(*via_family, *direct)) << name << " corner " << corner;
      EXPECT_LT(WorstLegError(robot, via_family->poses, readings), 1e-9) << name << " corner " << corner;
    }
  }
}

// Dietmaier's platform (strokes 0-10 m, readings about 1 m): all 40 modes real.
TEST(FkFamily, DietmaierFortyRealModes) {
  StatusOr<FkFamily> family = FkFamily::ForRobot(DietmaierRobot());
  ASSERT_TRUE(family.ok()) << family.status().message();
  EXPECT_EQ(family->hub_solutions(), 40);
  StatusOr<FkAllResult> fk = family->Solve(Eigen::Map<const LegReadings>(kDietmaierLengths));
  ASSERT_TRUE(fk.ok());
  EXPECT_EQ(fk->poses.size(), 40u);
  EXPECT_LT(WorstLegError(DietmaierRobot(), fk->poses, Eigen::Map<const LegReadings>(kDietmaierLengths)), 1e-9);
}

}  // namespace
}  // namespace hexcal

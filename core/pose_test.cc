#include "core/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::MatrixNear;
using ::hexcal::testing::Uniform;

// Elementary rotations written out by hand (right-handed, active).
// clang-format off
Eigen::Matrix3d HandRx(double q) {
  Eigen::Matrix3d r;
  r << 1, 0, 0,
       0, std::cos(q), -std::sin(q),
       0, std::sin(q), std::cos(q);
  return r;
}
Eigen::Matrix3d HandRy(double q) {
  Eigen::Matrix3d r;
  r << std::cos(q), 0, std::sin(q),
       0, 1, 0,
       -std::sin(q), 0, std::cos(q);
  return r;
}
Eigen::Matrix3d HandRz(double q) {
  Eigen::Matrix3d r;
  r << std::cos(q), -std::sin(q), 0,
       std::sin(q), std::cos(q), 0,
       0, 0, 1;
  return r;
}
// clang-format on

Eigen::Vector3d RandomAnglesRad() {
  return Eigen::Vector3d(DegToRad(Uniform(-170, 170)), DegToRad(Uniform(-80, 80)), DegToRad(Uniform(-170, 170)));
}

// xyz: R = Rz(q3) Ry(q2) Rx(q1), zyx: R = Rx(q3) Ry(q2) Rz(q1), from hand-written matrices.
TEST(Pose, RotationFromEulerMatchesHandWrittenProducts) {
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d q = RandomAnglesRad();
    EXPECT_TRUE(
        MatrixNear(RotationFromEuler(q, EulerConvention::kXYZ), HandRz(q[2]) * HandRy(q[1]) * HandRx(q[0]), 1e-14));
    EXPECT_TRUE(
        MatrixNear(RotationFromEuler(q, EulerConvention::kZYX), HandRx(q[2]) * HandRy(q[1]) * HandRz(q[0]), 1e-14));
  }
}

// A fixed case checked entry by entry: xyz with q = (90°, 0, 0) maps y to z.
uint64_t Bits(double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// The closed form is the product of Eigen's AngleAxis matrices bit for bit
// (the sign of zero included), so that no plan or candidate moves by an ulp.
TEST(Pose, RotationFromEulerIsTheAngleAxisProductExactly) {
  const auto axis = [](double q, const Eigen::Vector3d& u) { return Eigen::AngleAxisd(q, u).matrix(); };
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  const double special[] = {0.0, -0.0, kPi, -kPi, kPi / 2, 1e-300, -1e-17, 3.0};
  std::vector<Eigen::Vector3d> angles;
  for (double a : special) {
    for (double b : special) {
      for (double c : special) angles.emplace_back(a, b, c);
    }
  }
  for (int k = 0; k < 20000; ++k) angles.push_back(RandomAnglesRad());
  for (const Eigen::Vector3d& q : angles) {
    const Eigen::Matrix3d xyz = axis(q[2], z) * axis(q[1], y) * axis(q[0], x);
    const Eigen::Matrix3d zyx = axis(q[2], x) * axis(q[1], y) * axis(q[0], z);
    const Eigen::Matrix3d r_xyz = RotationFromEuler(q, EulerConvention::kXYZ);
    const Eigen::Matrix3d r_zyx = RotationFromEuler(q, EulerConvention::kZYX);
    for (int e = 0; e < 9; ++e) {
      ASSERT_EQ(Bits(r_xyz.data()[e]), Bits(xyz.data()[e])) << q.transpose();
      ASSERT_EQ(Bits(r_zyx.data()[e]), Bits(zyx.data()[e])) << q.transpose();
    }
  }
}

TEST(Pose, RotationFromEulerKnownCase) {
  const Eigen::Matrix3d r = RotationFromEuler(Eigen::Vector3d(kPi / 2, 0, 0), EulerConvention::kXYZ);
  EXPECT_TRUE(MatrixNear(r * Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), 1e-15));
  // zyx with q1 = 90° about z first: x goes to y.
  const Eigen::Matrix3d s = RotationFromEuler(Eigen::Vector3d(kPi / 2, 0, 0), EulerConvention::kZYX);
  EXPECT_TRUE(MatrixNear(s * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 1e-15));
}

// angles -> R -> angles gives the angles back (away from gimbal lock), both conventions.
TEST(Pose, EulerRoundTrip) {
  for (EulerConvention convention : {EulerConvention::kXYZ, EulerConvention::kZYX}) {
    for (int trial = 0; trial < 1000; ++trial) {
      const Eigen::Vector3d q = RandomAnglesRad();
      const Eigen::Vector3d back = EulerFromRotation(RotationFromEuler(q, convention), convention);
      EXPECT_TRUE(MatrixNear(back, q, 1e-12)) << EulerConventionName(convention);
    }
  }
}

// PoseFromVector / VectorFromPose are inverse to each other on [x, y, z, q1, q2, q3] (degrees).
TEST(Pose, VectorRoundTrip) {
  for (EulerConvention convention : {EulerConvention::kXYZ, EulerConvention::kZYX}) {
    for (int trial = 0; trial < 200; ++trial) {
      Vector6d v;
      v << Uniform(-100, 100), Uniform(-100, 100), Uniform(-100, 100), Uniform(-170, 170), Uniform(-80, 80),
          Uniform(-170, 170);
      const Pose pose = PoseFromVector(v, convention);
      EXPECT_TRUE(MatrixNear(pose.position, v.head<3>(), 0.0));
      EXPECT_TRUE(MatrixNear(VectorFromPose(pose, convention), v, 1e-10));
    }
  }
}

// A pose maps a platform point to P + R p.
TEST(Pose, ApplyToPoint) {
  Vector6d v;
  v << 1, 2, 3, 0, 0, 90;
  const Pose pose = PoseFromVector(v, EulerConvention::kXYZ);
  EXPECT_TRUE(MatrixNear(pose * Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 3, 3), 1e-15));
}

TEST(Pose, ParseEulerConvention) {
  EXPECT_EQ(ParseEulerConvention("xyz"), EulerConvention::kXYZ);
  EXPECT_EQ(ParseEulerConvention("zyx"), EulerConvention::kZYX);
  EXPECT_FALSE(ParseEulerConvention("abc").has_value());
  EXPECT_FALSE(ParseEulerConvention("XYZ").has_value());
  EXPECT_FALSE(ParseEulerConvention("").has_value());
  EXPECT_STREQ(EulerConventionName(EulerConvention::kZYX), "zyx");
}

// A rotation of 30° about an arbitrary axis, composed on a random rotation, is 30° away.
TEST(Pose, RotationDistanceOfKnownRotation) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  const Eigen::Matrix3d base = RotationFromEuler(RandomAnglesRad(), EulerConvention::kXYZ);
  const Eigen::Matrix3d turned = Eigen::AngleAxisd(DegToRad(30), axis).matrix() * base;
  EXPECT_NEAR(RadToDeg(RotationDistance(base, turned)), 30.0, 1e-12);
  EXPECT_NEAR(RadToDeg(RotationDistance(turned, base)), 30.0, 1e-12);
  EXPECT_NEAR(RotationDistance(base, base), 0.0, 1e-12);
  // Euler q1 = 30° alone (xyz) is a 30° rotation about x.
  EXPECT_NEAR(RadToDeg(RotationDistance(Eigen::Matrix3d::Identity(),
                                        RotationFromEuler(Eigen::Vector3d(DegToRad(30), 0, 0), EulerConvention::kXYZ))),
              30.0, 1e-12);
}

TEST(Pose, DegreeConversion) {
  EXPECT_DOUBLE_EQ(DegToRad(180), kPi);
  EXPECT_DOUBLE_EQ(RadToDeg(kPi / 6), 30.0);
}

// Pose algebra (issue 37): the properties Compose, Inverse and the camera
// registration's chain must have, on random rigid transforms.
Pose RandomPose() {
  Vector6d v;
  v << Uniform(-100, 100), Uniform(-100, 100), Uniform(-100, 100), Uniform(-170, 170), Uniform(-80, 80),
      Uniform(-170, 170);
  return PoseFromVector(v, EulerConvention::kXYZ);
}

::testing::AssertionResult PoseNear(const Pose& a, const Pose& b, double tolerance) {
  if (::testing::AssertionResult r = MatrixNear(a.rotation, b.rotation, tolerance); !r) return r << " (rotation)";
  if (::testing::AssertionResult r = MatrixNear(a.position, b.position, tolerance); !r) return r << " (position)";
  return ::testing::AssertionSuccess();
}

TEST(PoseAlgebra, InverseOfComposeIsIdentity) {
  for (int trial = 0; trial < 100; ++trial) {
    const Pose a_from_b = RandomPose();
    EXPECT_TRUE(PoseNear(Compose(Inverse(a_from_b), a_from_b), Pose{}, 1e-12)) << "trial " << trial;
    EXPECT_TRUE(PoseNear(Compose(a_from_b, Inverse(a_from_b)), Pose{}, 1e-12)) << "trial " << trial;
    EXPECT_TRUE(PoseNear(Inverse(Inverse(a_from_b)), a_from_b, 1e-12)) << "trial " << trial;
  }
}

TEST(PoseAlgebra, ComposeIsAssociativeAndActsAsTheProductOnPoints) {
  for (int trial = 0; trial < 100; ++trial) {
    const Pose a_from_b = RandomPose(), b_from_c = RandomPose(), c_from_d = RandomPose();
    EXPECT_TRUE(PoseNear(Compose(Compose(a_from_b, b_from_c), c_from_d), Compose(a_from_b, Compose(b_from_c, c_from_d)),
                         1e-9))
        << "trial " << trial;
    const Eigen::Vector3d p_in_c(Uniform(-10, 10), Uniform(-10, 10), Uniform(-10, 10));
    EXPECT_TRUE(MatrixNear(Compose(a_from_b, b_from_c) * p_in_c, a_from_b * (b_from_c * p_in_c), 1e-9));
    // The inverse of a product is the product of the inverses, reversed.
    EXPECT_TRUE(PoseNear(Inverse(Compose(a_from_b, b_from_c)), Compose(Inverse(b_from_c), Inverse(a_from_b)), 1e-9));
  }
}

TEST(PoseAlgebra, IdentityIsNeutral) {
  const Pose a_from_b = RandomPose();
  EXPECT_TRUE(PoseNear(Compose(Pose{}, a_from_b), a_from_b, 0));
  EXPECT_TRUE(PoseNear(Compose(a_from_b, Pose{}), a_from_b, 0));
  EXPECT_TRUE(PoseNear(Inverse(Pose{}), Pose{}, 0));
}

// The registration's chain A · Y = X · B both ways: what the camera sees at a
// platform pose maps back to that pose, and the reverse.
TEST(PoseAlgebra, CameraFromTargetAndBaseFromPlatformRoundTrip) {
  for (int trial = 0; trial < 100; ++trial) {
    const Pose base_from_camera = RandomPose(), platform_from_target = RandomPose();
    const Pose base_from_platform = RandomPose();
    const Pose camera_from_target = CameraFromTarget(base_from_camera, base_from_platform, platform_from_target);
    EXPECT_TRUE(PoseNear(BaseFromPlatform(base_from_camera, camera_from_target, platform_from_target),
                         base_from_platform, 1e-9))
        << "trial " << trial;
    EXPECT_TRUE(PoseNear(Compose(base_from_platform, platform_from_target), Compose(base_from_camera, camera_from_target),
                         1e-9));
    const Pose seen = RandomPose();
    EXPECT_TRUE(PoseNear(CameraFromTarget(base_from_camera,
                                          BaseFromPlatform(base_from_camera, seen, platform_from_target),
                                          platform_from_target),
                         seen, 1e-9))
        << "trial " << trial;
  }
}

// The chains are the products the registration documents, in that order.
TEST(PoseAlgebra, ChainsAreTheDocumentedProducts) {
  const Pose x = RandomPose(), y = RandomPose(), a = RandomPose(), b = RandomPose();
  EXPECT_TRUE(PoseNear(CameraFromTarget(x, a, y), Compose(Compose(Inverse(x), a), y), 0));
  EXPECT_TRUE(PoseNear(BaseFromPlatform(x, b, y), Compose(Compose(x, b), Inverse(y)), 0));
}

}  // namespace
}  // namespace hexcal

#include "vision/camera.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>

#include "core/pose.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

Camera RationalCamera() {
  Camera camera = SimulatedCamera();
  camera.model = CameraModel::kRational;
  camera.distortion = {0.4, -0.1, 0.0004, -0.0003, 0.02, 0.68, 0.02, 0.01};
  return camera;
}

// Points in front of the camera up to `max_angle_deg` off its axis.
std::vector<cv::Point3d> RandomRays(int count, double max_angle_deg) {
  std::vector<cv::Point3d> points;
  for (int i = 0; i < count; ++i) {
    const double theta = DegToRad(max_angle_deg) * std::sqrt(Uniform(0, 1)), phi = Uniform(0, 2 * kPi);
    const double depth = Uniform(0.5, 3);
    points.emplace_back(depth * std::sin(theta) * std::cos(phi), depth * std::sin(theta) * std::sin(phi),
                        depth * std::cos(theta));
  }
  return points;
}

// Project, Undistort and the pixel maps agree with each other for `camera`.
void ExpectRoundTrips(const Camera& camera, const std::vector<cv::Point3d>& points) {
  for (const cv::Point3d& point : points) {
    const Eigen::Vector3d p(point.x, point.y, point.z);
    const Eigen::Vector2d pixel = camera.Project(p);
    const std::optional<Eigen::Vector2d> ray = camera.Undistort(pixel);
    ASSERT_TRUE(ray.has_value()) << p.transpose();
    const Eigen::Vector2d expected = p.head<2>() / p.z();
    EXPECT_NEAR((*ray - expected).norm(), 0, 1e-11 * std::max(1.0, expected.squaredNorm())) << p.transpose();
    const Eigen::Vector2d ideal = *camera.IdealPixel(pixel);
    EXPECT_TRUE(testing::MatrixNear(camera.DistortedPixel(ideal), pixel, 1e-9));
  }
}

TEST(CameraTest, ModelNamesAndCoefficientCounts) {
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui})
    EXPECT_EQ(CameraModelFromName(CameraModelName(model)), model);
  EXPECT_FALSE(CameraModelFromName("omni").has_value());
  EXPECT_EQ(SimulatedCamera().DistortionCoefficients().size(), cv::Size(5, 1));
  EXPECT_EQ(RationalCamera().DistortionCoefficients().size(), cv::Size(8, 1));
  EXPECT_EQ(SimulatedFisheyeCamera().DistortionCoefficients().size(), cv::Size(4, 1));
  EXPECT_THAT(SimulatedFisheyeCamera().ParameterNames(),
              ::testing::ElementsAre("fx", "fy", "cx", "cy", "k1", "k2", "k3", "k4"));
  EXPECT_EQ(RationalCamera().ParameterValues().size(), 12u);
  Camera unused = SimulatedFisheyeCamera();
  unused.distortion[4] = 0.1;
  EXPECT_THAT(unused.Validate().message(), HasSubstr("coefficient 5 is not 0; the pinhole-equi model has 4"));
}

TEST(CameraTest, ProjectionMatchesOpenCvAndUndistortInvertsIt) {
  const Camera camera = SimulatedCamera();
  std::vector<cv::Point3d> points;
  for (int i = 0; i < 200; ++i) points.emplace_back(Uniform(-0.45, 0.45), Uniform(-0.35, 0.35), 1.0);
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.CameraMatrix(),
                    camera.DistortionCoefficients(), expected);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d pixel = camera.Project(Eigen::Vector3d(points[i].x, points[i].y, points[i].z));
    EXPECT_NEAR(pixel.x(), expected[i].x, 1e-9);
    EXPECT_NEAR(pixel.y(), expected[i].y, 1e-9);
    const std::optional<Eigen::Vector2d> ray = camera.Undistort(pixel);
    ASSERT_TRUE(ray.has_value());
    EXPECT_NEAR(ray->x(), points[i].x, 1e-11);
    EXPECT_NEAR(ray->y(), points[i].y, 1e-11);
    const Eigen::Vector2d ideal = *camera.IdealPixel(pixel);
    EXPECT_TRUE(testing::MatrixNear(camera.DistortedPixel(ideal), pixel, 1e-9));
  }
}

TEST(CameraTest, RationalModelMatchesOpenCvAndInverts) {
  const Camera camera = RationalCamera();
  const std::vector<cv::Point3d> points = RandomRays(300, 30);
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0.1, -0.2, 0.05), cv::Vec3d(0, 0, 0), camera.CameraMatrix(),
                    camera.DistortionCoefficients(), expected);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(Eigen::Vector3d(0.1, -0.2, 0.05).norm(), Eigen::Vector3d(0.1, -0.2, 0.05).normalized())
          .toRotationMatrix();
  std::vector<cv::Point3d> in_camera;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = rotation * Eigen::Vector3d(points[i].x, points[i].y, points[i].z);
    EXPECT_TRUE(testing::MatrixNear(camera.Project(p), Eigen::Vector2d(expected[i].x, expected[i].y), 1e-9)) << i;
    in_camera.emplace_back(p.x(), p.y(), p.z());
  }
  ExpectRoundTrips(camera, in_camera);
}

TEST(CameraTest, FisheyeMatchesOpenCvFisheye) {
  const Camera camera = SimulatedFisheyeCamera();
  const std::vector<cv::Point3d> points = RandomRays(300, 80);
  std::vector<cv::Point2d> projected;
  cv::fisheye::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                             cv::Matx33d(camera.CameraMatrix()), camera.DistortionCoefficients());
  std::vector<cv::Point2d> normalised, distorted;
  for (const cv::Point3d& p : points) normalised.emplace_back(p.x / p.z, p.y / p.z);
  cv::fisheye::distortPoints(normalised, distorted, cv::Matx33d(camera.CameraMatrix()),
                             camera.DistortionCoefficients());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p(points[i].x, points[i].y, points[i].z);
    EXPECT_TRUE(testing::MatrixNear(camera.Project(p), Eigen::Vector2d(projected[i].x, projected[i].y), 1e-9)) << i;
    const Eigen::Vector2d d = camera.Distort(p.head<2>() / p.z());
    const Eigen::Vector2d pixel(camera.fx * d.x() + camera.cx, camera.fy * d.y() + camera.cy);
    EXPECT_TRUE(testing::MatrixNear(pixel, Eigen::Vector2d(distorted[i].x, distorted[i].y), 1e-9)) << i;
  }
  ExpectRoundTrips(camera, points);
}

TEST(CameraTest, FisheyeUndistortsNearTheAxisAndAtWideAngles) {
  Camera camera = SimulatedFisheyeCamera();
  // On the axis and a hair off it.
  EXPECT_TRUE(testing::MatrixNear(*camera.Undistort({camera.cx, camera.cy}), Eigen::Vector2d(0, 0), 0));
  for (double offset : {1e-12, 1e-7, 1e-3}) {
    const Eigen::Vector3d p(offset, -0.5 * offset, 1);
    const std::optional<Eigen::Vector2d> ray = camera.Undistort(camera.Project(p));
    ASSERT_TRUE(ray.has_value());
    EXPECT_NEAR((*ray - p.head<2>()).norm(), 0, 1e-15 + 1e-12 * offset) << offset;
  }
  // Up to 89.5° off the axis (x up to 115), also from a neighbour's answer.
  for (double degrees : {60.0, 80.0, 85.0, 89.5}) {
    const double x = std::tan(DegToRad(degrees));
    const Eigen::Vector3d p(0.6 * x, -0.8 * x, 1);
    const Eigen::Vector2d pixel = camera.Project(p);
    const Eigen::Vector2d start = 0.9 * p.head<2>();
    for (const Eigen::Vector2d* guess : {static_cast<const Eigen::Vector2d*>(nullptr), &start}) {
      const std::optional<Eigen::Vector2d> ray = camera.Undistort(pixel, guess);
      ASSERT_TRUE(ray.has_value()) << degrees;
      EXPECT_NEAR((*ray - p.head<2>()).norm() / x, 0, 1e-11) << degrees;
    }
  }
  // 90° and beyond have pixels but no normalised (x, y).
  EXPECT_FALSE(camera.Undistort(camera.Project(Eigen::Vector3d(1, 0, 0))).has_value());
  EXPECT_FALSE(camera.Undistort(camera.Project(Eigen::Vector3d(1, 1, -0.5))).has_value());
  // A lens whose θ_d(θ) turns back before 90°: pixels past its turn do not invert.
  camera.distortion = {-0.3, 0, 0, 0};  // slope 1 - 0.9 θ² is 0 at θ = 60.4°
  const double theta_max = std::sqrt(1 / 0.9), theta_d_max = theta_max * (1 - 0.3 * theta_max * theta_max);
  EXPECT_TRUE(camera.Undistort({camera.cx + 0.999 * theta_d_max * camera.fx, camera.cy}).has_value());
  EXPECT_FALSE(camera.Undistort({camera.cx + 1.001 * theta_d_max * camera.fx, camera.cy}).has_value());
}

TEST(CameraTest, FieldOfViewSumsTheOffAxisAnglesOfTheImageEdges) {
  Camera pinhole = SimulatedCamera();
  pinhole.distortion = {};
  const FieldOfView ideal = CameraFieldOfView(pinhole);
  ASSERT_TRUE(ideal.horizontal_deg && ideal.vertical_deg && ideal.diagonal_deg);
  // The outer edge is half a pixel beyond the first and last pixel centres.
  const double left = pinhole.cx + 0.5, right = 1023.5 - pinhole.cx, top = pinhole.cy + 0.5,
               bottom = 767.5 - pinhole.cy;
  EXPECT_NEAR(*ideal.horizontal_deg, RadToDeg(std::atan(left / pinhole.fx) + std::atan(right / pinhole.fx)), 1e-12);
  EXPECT_NEAR(*ideal.vertical_deg, RadToDeg(std::atan(top / pinhole.fy) + std::atan(bottom / pinhole.fy)), 1e-12);
  EXPECT_NEAR(*ideal.diagonal_deg,
              RadToDeg(std::atan(std::hypot(left / pinhole.fx, top / pinhole.fy)) +
                       std::atan(std::hypot(right / pinhole.fx, bottom / pinhole.fy))),
              1e-12);
  // Barrel distortion (k1 < 0) shows more of the world on the same sensor.
  const FieldOfView barrel = CameraFieldOfView(SimulatedCamera());
  ASSERT_TRUE(barrel.horizontal_deg && barrel.diagonal_deg);
  EXPECT_GT(*barrel.horizontal_deg, *ideal.horizontal_deg + 1);
  // The fisheye's angle inverts Project, past 90° too (where Undistort has no (x, y)).
  const Camera fisheye = SimulatedFisheyeCamera();
  for (double degrees : {0.0, 10.0, 45.0, 89.0, 95.0, 110.0}) {
    const double theta = DegToRad(degrees);
    const Eigen::Vector2d pixel =
        fisheye.Project({std::sin(theta) * std::cos(0.3), std::sin(theta) * std::sin(0.3), std::cos(theta)});
    const std::optional<double> angle = fisheye.OffAxisAngle(pixel);
    ASSERT_TRUE(angle.has_value()) << degrees;
    EXPECT_NEAR(*angle, theta, 1e-12) << degrees;
  }
  // A lens whose θ_d(θ) turns back: no angle past the turn, so no field of view.
  Camera turning = fisheye;
  turning.distortion = {-0.3, 0, 0, 0};  // θ_d at most 0.608, at θ = 60.4°
  turning.fx = turning.fy = 200;         // the image's edge at θ_d = 2.6
  const FieldOfView none = CameraFieldOfView(turning);
  EXPECT_FALSE(none.horizontal_deg.has_value());
  EXPECT_FALSE(none.diagonal_deg.has_value());
}

TEST(CameraTest, IdealPixelMapMatchesIdealPixel) {
  for (const Camera& camera : {SimulatedCamera(), RationalCamera(), SimulatedFisheyeCamera()}) {
    const IdealPixelMap map(camera);
    for (const auto& [u, v] : {std::pair{0, 0}, std::pair{1023, 767}, std::pair{500, 400}, std::pair{17, 700}}) {
      const Eigen::Vector2d expected = *camera.IdealPixel(Eigen::Vector2d(u, v));
      EXPECT_TRUE(testing::MatrixNear(map.At(u, v), expected, 1e-3 * std::max(1.0, expected.norm() / 1000)))
          << CameraModelName(camera.model) << " " << u << "," << v;
    }
  }
}

}  // namespace
}  // namespace hexcal

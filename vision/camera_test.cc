#include "vision/camera.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::Uniform;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

void ExpectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(a.distortion[i], b.distortion[i]) << i;
}

std::string ParseError(const std::string& text) {
  StatusOr<Camera> camera = ParseCameraFile(text, "cam.yaml");
  EXPECT_FALSE(camera.ok()) << text;
  return camera.ok() ? "" : camera.status().message();
}

TEST(CameraTest, OpenCvYamlRoundTripIsExact) {
  Camera camera = SimulatedCamera();
  camera.fx = 903.2 + 1e-9;
  camera.distortion[2] = 1.0 / 3e4;
  CameraFileExtras extras;
  extras.views = 20;
  extras.rms_px = 0.05;
  extras.std_dev = {0.1, 0.1, 0.2, 0.2, 1e-3, 2e-3, 1e-5, 1e-5, 3e-3};
  extras.per_view_rms_px = {0.04, 0.06};
  extras.comment = "line one\nline two";
  const std::string text = CameraToOpenCvYaml(camera, extras);
  StatusOr<Camera> back = ParseCameraFile(text, "round-trip");
  ASSERT_TRUE(back.ok()) << back.status().message();
  ExpectSameCamera(*back, camera);
  // OpenCV itself reads the extras.
  cv::FileStorage storage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  cv::Mat std_dev;
  storage["intrinsics_std_dev"] >> std_dev;
  EXPECT_EQ(std_dev.total(), 9u);
  EXPECT_EQ(static_cast<int>(storage["nr_of_frames"]), 20);
  EXPECT_EQ(static_cast<double>(storage["avg_reprojection_error"]), 0.05);
}

TEST(CameraTest, ResourceFileAndBuiltInNameAreTheSimulatedCamera) {
  StatusOr<Camera> file = LoadCamera((SourceDir() / "resources/cameras/sim-4.2mm-1024x768.yaml").string());
  ASSERT_TRUE(file.ok()) << file.status().message();
  ExpectSameCamera(*file, SimulatedCamera());
  StatusOr<Camera> builtin = LoadCamera(kSimulatedCameraName);
  ASSERT_TRUE(builtin.ok());
  ExpectSameCamera(*builtin, SimulatedCamera());
  EXPECT_NEAR(SimulatedCamera().fx, 4.2 / 0.00465, 0.05);
}

TEST(CameraTest, ReadsRosCameraInfo) {
  StatusOr<Camera> camera = LoadCamera((SourceDir() / "tests/data/cameras/ros_camera_info.yaml").string());
  ASSERT_TRUE(camera.ok()) << camera.status().message();
  ExpectSameCamera(*camera, SimulatedCamera());
  // The CameraInfo message's own layout.
  StatusOr<Camera> message = ParseCameraFile(
      "width: 640\nheight: 480\ndistortion_model: plumb_bob\nD: [0.1, -0.2, 0, 0, 0]\n"
      "K: [500, 0, 320, 0, 510, 240, 0, 0, 1]\n",
      "info.yaml");
  ASSERT_TRUE(message.ok()) << message.status().message();
  EXPECT_EQ(message->fy, 510);
  EXPECT_EQ(message->distortion[1], -0.2);
}

TEST(CameraTest, ErrorsAreClear) {
  StatusOr<Camera> fisheye = LoadCamera((SourceDir() / "tests/data/cameras/fisheye_camera_info.yaml").string());
  ASSERT_FALSE(fisheye.ok());
  EXPECT_THAT(fisheye.status().message(), HasSubstr("distortion_model: 'equidistant' is not supported"));
  EXPECT_THAT(ParseError(""), HasSubstr("camera file 'cam.yaml': empty file"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\n"), HasSubstr("camera_matrix.data: expected a list"));
  EXPECT_THAT(ParseError("%YAML:1.0\n---\nimage_width: 640\n"), HasSubstr("image_height: missing"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\ncamera_matrix: {data: [500, 2, 320, 0, 500, 240, 0, 0, "
                         "1]}\ndistortion_coefficients: {data: [0, 0, 0, 0, 0]}\n"),
              HasSubstr("no skew"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\ncamera_matrix: {data: [-5, 0, 320, 0, 500, 240, 0, 0, "
                         "1]}\ndistortion_coefficients: {data: [0, 0, 0, 0, 0]}\n"),
              HasSubstr("must be positive"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\ncamera_matrix: {data: [500, 0, 320, 0, 500, 240, 0, 0, "
                         "1]}\ndistortion_coefficients: {data: [0, 0, 0, 0, 0, 0.3, 0, 0]}\n"),
              HasSubstr("coefficient 6 is not 0"));
  EXPECT_THAT(ParseError("%YAML:1.0\n---\ncamera_matrix: [ 1, 2\n"), HasSubstr("camera file 'cam.yaml'"));
  StatusOr<Camera> missing = LoadCamera("no-camera.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("no-camera.yaml: no such file"));
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

TEST(CameraTest, IdealPixelMapMatchesIdealPixel) {
  const Camera camera = SimulatedCamera();
  const IdealPixelMap map(camera);
  for (const auto& [u, v] : {std::pair{0, 0}, std::pair{1023, 767}, std::pair{500, 400}, std::pair{17, 700}}) {
    const Eigen::Vector2d expected = *camera.IdealPixel(Eigen::Vector2d(u, v));
    EXPECT_TRUE(testing::MatrixNear(map.At(u, v), expected, 1e-3)) << u << "," << v;
  }
}

}  // namespace
}  // namespace hexcal

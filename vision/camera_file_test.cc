// Camera files (vision/camera_file.cc): OpenCV YAML and XML, ROS camera_info,
// Kalibr camchain; every model written and read back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tests/test_support.h"
#include "vision/camera.h"
#include "vision/camera_expect.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;
using ::testing::HasSubstr;
using ::testing::Not;

std::string ParseError(const std::string& text) {
  return testing::ErrorMessage(ParseCameraFile(text, "cam.yaml"), text);
}

// `text`, read back by hexcal, is `camera` exactly.
void ExpectReadsBackAs(const std::string& text, const std::string& source, const Camera& camera) {
  StatusOr<Camera> back = ParseCameraFile(text, source);
  ASSERT_TRUE(back.ok()) << back.status().message();
  ExpectSameCamera(*back, camera);
}

Camera WithModel(CameraModel model) {
  Camera camera = SimulatedCamera();
  camera.model = model;
  if (model == CameraModel::kRational) camera.distortion = {0.4, -0.1, 1.0 / 3e4, -0.0003, 0.02, 0.68, 0.02, 0.01};
  if (model == CameraModel::kPinholeEqui) camera.distortion = {0.05, -0.02, 0.004, -1.0 / 3e4};
  return camera;
}

TEST(CameraFileTest, OpenCvYamlRoundTripIsExact) {
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
  EXPECT_THAT(text, Not(HasSubstr("distortion_model")));  // the radtan file is OpenCV's sample's
  EXPECT_THAT(text, HasSubstr("# standard deviations of fx, fy, cx, cy, k1, k2, p1, p2, k3\n"));
  ExpectReadsBackAs(text, "round-trip", camera);
  // OpenCV itself reads the extras.
  cv::FileStorage storage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  cv::Mat std_dev;
  storage["intrinsics_std_dev"] >> std_dev;
  EXPECT_EQ(std_dev.total(), 9u);
  EXPECT_EQ(static_cast<int>(storage["nr_of_frames"]), 20);
  EXPECT_EQ(static_cast<double>(storage["avg_reprojection_error"]), 0.05);
}

TEST(CameraFileTest, EveryModelRoundTripsThroughOpenCvYamlAndXml) {
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui}) {
    const Camera camera = WithModel(model);
    const std::string text = CameraToOpenCvYaml(camera);
    ExpectReadsBackAs(text, "round-trip", camera);
    // OpenCV reads the coefficients as the model's vector (1x5, 1x8, 1x4).
    cv::FileStorage storage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    cv::Mat d;
    storage["distortion_coefficients"] >> d;
    EXPECT_EQ(static_cast<int>(d.total()), camera.NumCoefficients());
    // The same through OpenCV's XML.
    cv::FileStorage xml("camera.xml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    xml << "image_width" << camera.width << "image_height" << camera.height;
    xml << "camera_matrix" << cv::Mat(cv::Matx33d(camera.CameraMatrix()));
    xml << "distortion_coefficients" << camera.DistortionCoefficients();
    if (model == CameraModel::kPinholeEqui)
      xml << "distortion_model"
          << "fisheye";
    ExpectReadsBackAs(xml.releaseAndGetString(), "camera.xml", camera);
  }
  EXPECT_THAT(CameraToOpenCvYaml(WithModel(CameraModel::kRational)), HasSubstr("flags: 16384\n"));
  EXPECT_THAT(CameraToOpenCvYaml(WithModel(CameraModel::kPinholeEqui)), HasSubstr("distortion_model: equidistant\n"));
}

TEST(CameraFileTest, OpenCvCoefficientCountsChooseTheModel) {
  const std::string head =
      "image_width: 640\nimage_height: 480\ncamera_matrix: {data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n";
  StatusOr<Camera> four = ParseCameraFile(head + "distortion_coefficients: {data: [0.1, 0, 0, 0]}\n", "c.yaml");
  ASSERT_TRUE(four.ok()) << four.status().message();
  EXPECT_EQ(four->model, CameraModel::kRadTan);
  StatusOr<Camera> eight =
      ParseCameraFile(head + "distortion_coefficients: {data: [0, 0, 0, 0, 0, 0.3, 0, 0]}\n", "c.yaml");
  ASSERT_TRUE(eight.ok()) << eight.status().message();
  EXPECT_EQ(eight->model, CameraModel::kRational);
  EXPECT_EQ(eight->distortion[5], 0.3);
  StatusOr<Camera> fisheye = ParseCameraFile(
      head + "distortion_model: fisheye\ndistortion_coefficients: {data: [0.1, 0, 0, 0.2]}\n", "c.yaml");
  ASSERT_TRUE(fisheye.ok()) << fisheye.status().message();
  EXPECT_EQ(fisheye->model, CameraModel::kPinholeEqui);
  EXPECT_EQ(fisheye->distortion[3], 0.2);
  EXPECT_THAT(ParseError(head + "distortion_coefficients: {data: [0, 0, 0, 0, 0, 0, 0, 0, 0.1, 0, 0, 0]}\n"),
              HasSubstr("distortion_coefficients: coefficient 9 is not 0; the rational model has k1, k2, p1, p2, k3, "
                        "k4, k5, k6"));
  EXPECT_THAT(
      ParseError(head + "distortion_model: plumb_bob\ndistortion_coefficients: {data: [0, 0, 0, 0, 0, 0.3, 0, 0]}\n"),
      HasSubstr("coefficient 6 is not 0; the radtan model has k1, k2, p1, p2, k3"));
  EXPECT_THAT(
      ParseError(head + "distortion_model: equidistant\ndistortion_coefficients: {data: [0.1, 0, 0, 0, 0.5]}\n"),
      HasSubstr("coefficient 5 is not 0; the pinhole-equi model has k1, k2, k3, k4"));
  EXPECT_THAT(ParseError(head + "distortion_model: fov\ndistortion_coefficients: {data: [0.1]}\n"),
              HasSubstr("camera file 'cam.yaml': distortion_model: 'fov' is not supported; expected plumb_bob, "
                        "rational_polynomial or equidistant"));
}

TEST(CameraFileTest, ResourceFileAndBuiltInNameAreTheSimulatedCamera) {
  StatusOr<Camera> file = LoadCamera((SourceDir() / "resources/cameras/sim-4.2mm-1024x768.yaml").string());
  ASSERT_TRUE(file.ok()) << file.status().message();
  ExpectSameCamera(*file, SimulatedCamera());
  StatusOr<Camera> builtin = LoadCamera(kSimulatedCameraName);
  ASSERT_TRUE(builtin.ok());
  ExpectSameCamera(*builtin, SimulatedCamera());
  EXPECT_NEAR(SimulatedCamera().fx, 4.2 / 0.00465, 0.05);
}

TEST(CameraFileTest, ReadsRosCameraInfoOfEveryModel) {
  StatusOr<Camera> camera = LoadCamera((SourceDir() / "tests/data/cameras/ros_camera_info.yaml").string());
  ASSERT_TRUE(camera.ok()) << camera.status().message();
  ExpectSameCamera(*camera, SimulatedCamera());
  StatusOr<Camera> fisheye = LoadCamera((SourceDir() / "tests/data/cameras/fisheye_camera_info.yaml").string());
  ASSERT_TRUE(fisheye.ok()) << fisheye.status().message();
  EXPECT_EQ(fisheye->model, CameraModel::kPinholeEqui);
  EXPECT_EQ(fisheye->distortion[1], 0.01);
  // The CameraInfo message's own layout.
  StatusOr<Camera> message = ParseCameraFile(
      "width: 640\nheight: 480\ndistortion_model: plumb_bob\nD: [0.1, -0.2, 0, 0, 0]\n"
      "K: [500, 0, 320, 0, 510, 240, 0, 0, 1]\n",
      "info.yaml");
  ASSERT_TRUE(message.ok()) << message.status().message();
  EXPECT_EQ(message->fy, 510);
  EXPECT_EQ(message->distortion[1], -0.2);
  StatusOr<Camera> rational = ParseCameraFile(
      "width: 640\nheight: 480\ndistortion_model: rational_polynomial\nD: [0.1, -0.2, 0, 0, 0, 0.5, 0, 0]\n"
      "K: [500, 0, 320, 0, 510, 240, 0, 0, 1]\n",
      "info.yaml");
  ASSERT_TRUE(rational.ok()) << rational.status().message();
  EXPECT_EQ(rational->model, CameraModel::kRational);
  EXPECT_EQ(rational->distortion[5], 0.5);
}

TEST(CameraFileTest, ReadsKalibrCamchain) {
  StatusOr<Camera> tumvi = LoadCamera((SourceDir() / "tests/data/cameras/kalibr_tumvi_camchain.yaml").string());
  ASSERT_TRUE(tumvi.ok()) << tumvi.status().message();
  EXPECT_EQ(tumvi->model, CameraModel::kPinholeEqui);
  EXPECT_EQ(tumvi->width, 512);
  EXPECT_EQ(tumvi->height, 512);
  EXPECT_EQ(tumvi->fx, 190.97847715128717);
  EXPECT_EQ(tumvi->fy, 190.9733070521226);
  EXPECT_EQ(tumvi->cx, 254.93170605935475);
  EXPECT_EQ(tumvi->cy, 256.8974428996504);
  EXPECT_EQ(tumvi->distortion[0], 0.0034823894022493434);
  EXPECT_EQ(tumvi->distortion[3], 0.00020293673591811182);
  // Written as OpenCV YAML, it reads back the same.
  ExpectReadsBackAs(CameraToOpenCvYaml(*tumvi), "tumvi.yaml", *tumvi);
  // A camera at the top level, radtan (k3 = 0); of several cameras, cam0.
  const std::string radtan =
      "camera_model: pinhole\nintrinsics: [458.654, 457.296, 367.215, 248.375]\ndistortion_model: radtan\n"
      "distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\nresolution: [752, 480]\n";
  StatusOr<Camera> euroc = ParseCameraFile(radtan, "euroc.yaml");
  ASSERT_TRUE(euroc.ok()) << euroc.status().message();
  EXPECT_EQ(euroc->model, CameraModel::kRadTan);
  EXPECT_EQ(euroc->fy, 457.296);
  EXPECT_EQ(euroc->distortion[3], 1.76187114e-05);
  EXPECT_EQ(euroc->distortion[4], 0);
  std::string two = "cam0:\n";
  for (const char* line : {"camera_model: pinhole", "intrinsics: [400, 401, 320, 240]", "distortion_model: radtan",
                           "distortion_coeffs: [0.1, 0, 0, 0]", "resolution: [640, 480]"})
    two += "  " + std::string(line) + "\n";
  two += "cam1:\n  camera_model: omni\n";
  StatusOr<Camera> first = ParseCameraFile(two, "camchain.yaml");
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->fy, 401);
}

TEST(CameraFileTest, KalibrErrorsNameTheKey) {
  const std::string cam = "cam0:\n  camera_model: pinhole\n  resolution: [640, 480]\n";
  EXPECT_THAT(ParseError("cam0:\n  camera_model: omni\n"),
              HasSubstr("camera file 'cam.yaml': cam0.camera_model: 'omni' is not supported; expected pinhole"));
  EXPECT_THAT(ParseError(cam + "  intrinsics: [400, 400, 320]\n"),
              HasSubstr("cam0.intrinsics: expected 4 numbers (fu, fv, pu, pv), found 3"));
  EXPECT_THAT(
      ParseError(cam + "  intrinsics: [400, 400, 320, 240]\n  distortion_model: fov\n  distortion_coeffs: [0.9]\n"),
      HasSubstr("cam0.distortion_model: 'fov' is not supported; expected radtan, equidistant or none"));
  EXPECT_THAT(
      ParseError(
          cam + "  intrinsics: [400, 400, 320, 240]\n  distortion_model: equidistant\n  distortion_coeffs: [0.1, 0]\n"),
      HasSubstr("cam0.distortion_coeffs: expected 4 numbers for 'equidistant', found 2"));
  EXPECT_THAT(ParseError("camera_model: pinhole\nintrinsics: [400, 400, 320, 240]\ndistortion_model: none\n"
                         "resolution: [640.5, 480]\n"),
              HasSubstr("camera file 'cam.yaml': resolution: expected 2 whole numbers (width, height)"));
  EXPECT_THAT(ParseError("cam0: [1, 2]\n"), HasSubstr("cam0: expected a Kalibr camera"));
}

TEST(CameraFileTest, ErrorsAreClear) {
  EXPECT_THAT(ParseError(""), HasSubstr("camera file 'cam.yaml': empty file"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\n"), HasSubstr("camera_matrix.data: expected a list"));
  EXPECT_THAT(ParseError("%YAML:1.0\n---\nimage_width: 640\n"), HasSubstr("image_height: missing"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\ncamera_matrix: {data: [500, 2, 320, 0, 500, 240, 0, 0, "
                         "1]}\ndistortion_coefficients: {data: [0, 0, 0, 0, 0]}\n"),
              HasSubstr("no skew"));
  EXPECT_THAT(ParseError("image_width: 640\nimage_height: 480\ncamera_matrix: {data: [-5, 0, 320, 0, 500, 240, 0, 0, "
                         "1]}\ndistortion_coefficients: {data: [0, 0, 0, 0, 0]}\n"),
              HasSubstr("must be positive"));
  EXPECT_THAT(ParseError("%YAML:1.0\n---\ncamera_matrix: [ 1, 2\n"), HasSubstr("camera file 'cam.yaml'"));
  // A secret-looking value is not echoed beyond a short excerpt.
  const std::string message = ParseError("distortion_model: " + std::string(200, 'x') + "\n");
  EXPECT_LT(message.size(), 160u);
  StatusOr<Camera> missing = LoadCamera("no-camera.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("no-camera.yaml: no such file"));
}

}  // namespace
}  // namespace hexcal

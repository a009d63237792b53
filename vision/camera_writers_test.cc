// Camera files out (vision/camera_writers.cc): every model through every
// format reads back the same camera, bit for bit; what Kalibr cannot hold is
// refused by name; OpenCV reads the OpenCV file; ROS's layout; numbers that
// YAML 1.1 (PyYAML) takes for floats.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <regex>
#include <sstream>

#include "vision/camera.h"
#include "vision/camera_expect.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

constexpr CameraFileFormat kFormats[] = {CameraFileFormat::kOpenCv, CameraFileFormat::kRos, CameraFileFormat::kKalibr};

// Numbers whose text is easy to get wrong: a whole fx (903 reads as a YAML
// int), 1e-05 (a YAML 1.1 string unless it has a '.'), 1/3e4 (17 digits), a
// negative zero, a sub-pixel step of 1e-9 on a large value.
Camera TrickyCamera(CameraModel model) {
  Camera camera = SimulatedCamera();
  camera.model = model;
  camera.fx = 903;
  camera.fy = 903.2 + 1e-9;
  camera.cy = 1.0 / 3;
  if (model == CameraModel::kRadTan) camera.distortion = {-0.28, 1e-05, 1.0 / 3e4, -0.0, 0};
  if (model == CameraModel::kRational) camera.distortion = {0.4, -0.1, 1.0 / 3e4, -0.0003, 0.02, 0.68, 1e-05, 2e-20};
  if (model == CameraModel::kPinholeEqui) camera.distortion = {0.05, -0.02, 1e-05, -1.0 / 3e4};
  return camera;
}

TEST(CameraWritersTest, EveryModelRoundTripsThroughEveryFormatExactly) {
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui}) {
    for (CameraFileFormat format : kFormats) {
      SCOPED_TRACE(std::string(CameraModelName(model)) + " as " + CameraFileFormatName(format));
      const Camera camera = TrickyCamera(model);
      StatusOr<std::string> text = CameraToText(camera, format);
      if (model == CameraModel::kRational && format == CameraFileFormat::kKalibr) {
        ASSERT_FALSE(text.ok());
        EXPECT_THAT(text.status().message(), HasSubstr("Kalibr has no rational model"));
        continue;
      }
      ASSERT_TRUE(text.ok()) << text.status().message();
      StatusOr<Camera> back = ParseCameraFile(*text, "written.yaml");
      ASSERT_TRUE(back.ok()) << back.status().message();
      ExpectSameCamera(*back, camera);
      EXPECT_TRUE(std::signbit(back->distortion[model == CameraModel::kRadTan ? 3 : 0]) ==
                  std::signbit(camera.distortion[model == CameraModel::kRadTan ? 3 : 0]));
    }
  }
}

TEST(CameraWritersTest, OpenCvReadsTheOpenCvFileOfEveryModel) {
  for (CameraModel model : {CameraModel::kRadTan, CameraModel::kRational, CameraModel::kPinholeEqui}) {
    const Camera camera = TrickyCamera(model);
    StatusOr<std::string> text = CameraToText(camera, CameraFileFormat::kOpenCv);
    ASSERT_TRUE(text.ok()) << text.status().message();
    cv::FileStorage storage(*text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    ASSERT_TRUE(storage.isOpened());
    cv::Mat k, d;
    storage["camera_matrix"] >> k;
    storage["distortion_coefficients"] >> d;
    EXPECT_EQ(static_cast<int>(storage["image_width"]), camera.width);
    EXPECT_EQ(static_cast<int>(storage["image_height"]), camera.height);
    ASSERT_EQ(k.total(), 9u);
    EXPECT_EQ(cv::norm(k, cv::Mat(cv::Matx33d(camera.CameraMatrix())), cv::NORM_INF), 0);
    ASSERT_EQ(static_cast<int>(d.total()), camera.NumCoefficients());
    for (int i = 0; i < camera.NumCoefficients(); ++i) EXPECT_EQ(d.at<double>(i), camera.distortion[i]) << i;
  }
}

TEST(CameraWritersTest, RosFileIsCameraCalibrationParsersLayout) {
  StatusOr<std::string> text = CameraToText(SimulatedCamera(), CameraFileFormat::kRos, "hexcal_sim");
  ASSERT_TRUE(text.ok()) << text.status().message();
  EXPECT_EQ(*text,
            "image_width: 1024\n"
            "image_height: 768\n"
            "camera_name: hexcal_sim\n"
            "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [903.2, 0.0, 515.3, 0.0, 903.2, 380.1, 0.0, 0.0, 1.0]\n"
            "distortion_model: plumb_bob\n"
            "distortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [-0.28, 0.09, 0.0004, -0.0003, -0.012]\n"
            "rectification_matrix:\n  rows: 3\n  cols: 3\n  data: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]\n"
            "projection_matrix:\n  rows: 3\n  cols: 4\n"
            "  data: [903.2, 0.0, 515.3, 0.0, 0.0, 903.2, 380.1, 0.0, 0.0, 0.0, 1.0, 0.0]\n");
  StatusOr<std::string> rational = CameraToText(TrickyCamera(CameraModel::kRational), CameraFileFormat::kRos);
  ASSERT_TRUE(rational.ok());
  EXPECT_THAT(*rational, HasSubstr("distortion_model: rational_polynomial\ndistortion_coefficients:\n  rows: 1\n"
                                   "  cols: 8\n"));
  StatusOr<std::string> fisheye = CameraToText(TrickyCamera(CameraModel::kPinholeEqui), CameraFileFormat::kRos);
  ASSERT_TRUE(fisheye.ok());
  EXPECT_THAT(*fisheye, HasSubstr("distortion_model: equidistant\ndistortion_coefficients:\n  rows: 1\n  cols: 4\n"));
}

TEST(CameraWritersTest, KalibrFileIsACamchainOfOneCamera) {
  Camera radtan = SimulatedCamera();
  radtan.distortion[4] = 0;
  StatusOr<std::string> text = CameraToText(radtan, CameraFileFormat::kKalibr);
  ASSERT_TRUE(text.ok()) << text.status().message();
  EXPECT_THAT(*text, HasSubstr("\ncam0:\n  camera_model: pinhole\n  intrinsics: [903.2, 903.2, 515.3, 380.1]\n"
                               "  distortion_model: radtan\n  distortion_coeffs: [-0.28, 0.09, 0.0004, -0.0003]\n"
                               "  resolution: [1024, 768]\n"));
  StatusOr<std::string> fisheye = CameraToText(SimulatedFisheyeCamera(), CameraFileFormat::kKalibr);
  ASSERT_TRUE(fisheye.ok());
  EXPECT_THAT(*fisheye,
              HasSubstr("  distortion_model: equidistant\n  distortion_coeffs: [0.05, -0.02, 0.004, -0.0005]\n"));
}

TEST(CameraWritersTest, KalibrRefusesWhatItCannotHoldByName) {
  StatusOr<std::string> rational = CameraToKalibrYaml(TrickyCamera(CameraModel::kRational));
  ASSERT_FALSE(rational.ok());
  EXPECT_EQ(rational.status().kind(), StatusKind::kBadInput);
  EXPECT_THAT(rational.status().message(), HasSubstr("Kalibr has no rational model (k1 k2 p1 p2 k3 k4 k5 k6)"));
  StatusOr<std::string> k3 = CameraToKalibrYaml(SimulatedCamera());
  ASSERT_FALSE(k3.ok());
  EXPECT_THAT(k3.status().message(), HasSubstr("k3 = -0.012, and Kalibr's radtan has k1 k2 p1 p2 only"));
  Camera negative = SimulatedFisheyeCamera();
  negative.cx = -2.5;
  StatusOr<std::string> principal = CameraToKalibrYaml(negative);
  ASSERT_FALSE(principal.ok());
  EXPECT_THAT(principal.status().message(), HasSubstr("principal point (-2.5, 380.1) is negative"));
}

TEST(CameraWritersTest, RosAndKalibrNumbersAreYaml11Floats) {
  // PyYAML's float pattern (yaml/resolver.py), without the inf and nan forms.
  const std::regex yaml11_float(R"([-+]?[0-9][0-9_]*\.[0-9_]*([eE][-+][0-9]+)?)");
  const std::regex list(R"((data|intrinsics|distortion_coeffs): \[([^\]]*)\])");
  Camera camera = TrickyCamera(CameraModel::kPinholeEqui);
  camera.cx = 512;
  for (CameraFileFormat format : {CameraFileFormat::kRos, CameraFileFormat::kKalibr}) {
    StatusOr<std::string> text = CameraToText(camera, format);
    ASSERT_TRUE(text.ok()) << text.status().message();
    int numbers = 0;
    for (std::sregex_iterator it(text->begin(), text->end(), list), end; it != end; ++it) {
      std::stringstream items((*it)[2].str());
      for (std::string item; std::getline(items, item, ',');) {
        item.erase(0, item.find_first_not_of(' '));
        EXPECT_TRUE(std::regex_match(item, yaml11_float)) << item << " in " << (*it)[0];
        ++numbers;
      }
    }
    EXPECT_EQ(numbers, format == CameraFileFormat::kRos ? 9 + 4 + 9 + 12 : 4 + 4);
    EXPECT_THAT(*text, HasSubstr("1.0e-05"));
    EXPECT_THAT(*text, HasSubstr("903.0, "));
    EXPECT_THAT(*text, HasSubstr("512.0"));
  }
}

TEST(CameraWritersTest, FormatNamesAndBadInputs) {
  for (CameraFileFormat format : kFormats) EXPECT_EQ(CameraFileFormatFromName(CameraFileFormatName(format)), format);
  EXPECT_FALSE(CameraFileFormatFromName("matlab"));
  EXPECT_FALSE(CameraFileFormatFromName("ROS"));
  StatusOr<std::string> name = CameraToText(SimulatedCamera(), CameraFileFormat::kRos, "left cam: x");
  ASSERT_FALSE(name.ok());
  EXPECT_THAT(name.status().message(), HasSubstr("camera name 'left cam: x': ROS takes letters, digits and '_' only"));
  EXPECT_TRUE(IsRosCameraName("narrow_stereo_2"));
  EXPECT_FALSE(IsRosCameraName(""));
  Camera broken = SimulatedCamera();
  broken.fx = -1;
  for (CameraFileFormat format : kFormats) {
    StatusOr<std::string> text = CameraToText(broken, format);
    ASSERT_FALSE(text.ok());
    EXPECT_THAT(text.status().message(), HasSubstr("must be positive"));
  }
}

}  // namespace
}  // namespace hexcal

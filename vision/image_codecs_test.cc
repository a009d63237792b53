// The image codecs come from a module opened on first use (image_codecs.h):
// this test links no OpenCV codec itself, so it sees the module arrive.
#include "vision/image_codecs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/test_support.h"

namespace hexcal {
namespace {

bool Mapped(const std::string& library) {
  std::ifstream maps("/proc/self/maps");
  std::stringstream text;
  text << maps.rdbuf();
  return text.str().find(library) != std::string::npos;
}

TEST(ImageCodecs, LoadedOnlyOnFirstUseThenRoundTrip) {
  EXPECT_FALSE(Mapped("libopencv_imgcodecs")) << "the executable must not load imgcodecs at start";
  cv::Mat image(17, 23, CV_8UC1);
  cv::randu(image, 0, 256);
  StatusOr<std::string> png = EncodePng(image);
  ASSERT_TRUE(png.ok()) << png.status().message();
  EXPECT_TRUE(Mapped("libhexcal_opencv_io"));
  EXPECT_EQ(png->substr(1, 3), "PNG");
  StatusOr<cv::Mat> decoded = DecodeImage(*png);
  ASSERT_TRUE(decoded.ok()) << decoded.status().message();
  EXPECT_EQ(cv::norm(image, *decoded, cv::NORM_INF), 0);
}

TEST(ImageCodecs, BadBytesAndFilesAreErrors) {
  StatusOr<cv::Mat> garbage = DecodeImage(std::string(100, 'x'));
  ASSERT_FALSE(garbage.ok());
  EXPECT_NE(garbage.status().message().find("cannot decode"), std::string::npos);
  EXPECT_FALSE(DecodeImage("").ok());
  EXPECT_FALSE(EncodePng(cv::Mat()).ok());
  testing::TempDir dir;
  const std::string text = dir.File("notes.txt");
  std::ofstream(text) << "not an image";
  StatusOr<cv::Mat> read = ReadImageFile(text);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.status().message().find("not an image OpenCV can read"), std::string::npos);
  StatusOr<std::unique_ptr<VideoStream>> video = OpenVideoFile(text);
  ASSERT_FALSE(video.ok());
  EXPECT_NE(video.status().message().find("not a video OpenCV can read"), std::string::npos);
}

}  // namespace
}  // namespace hexcal

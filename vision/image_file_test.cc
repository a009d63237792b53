#include "vision/image_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "vision/image_header.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

std::string Encode(const cv::Mat& image, const std::string& extension) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes));
  return std::string(bytes.begin(), bytes.end());
}

// An APP1 EXIF segment holding one IFD entry: Orientation (274) = value.
std::string ExifOrientationSegment(uint16_t value) {
  std::string tiff("II*\0\x08\0\0\0", 8);               // little-endian TIFF, IFD0 at byte 8
  tiff += std::string("\x01\0", 2);                       // one entry
  tiff += std::string("\x12\x01\x03\0\x01\0\0\0", 8);     // tag 274, SHORT, count 1
  tiff += std::string(1, static_cast<char>(value)) + std::string(3, '\0');
  tiff += std::string(4, '\0');                           // no next IFD
  const std::string payload = std::string("Exif\0\0", 6) + tiff;
  const size_t length = payload.size() + 2;
  return std::string("\xFF\xE1", 2) + static_cast<char>(length >> 8) + static_cast<char>(length & 0xFF) + payload;
}

TEST(ImageFileTest, SixteenBitImagesAreScaledByTheirRange) {
  cv::Mat twelve_bit(20, 64, CV_16UC1);
  for (int col = 0; col < 64; ++col) twelve_bit.col(col).setTo(static_cast<uint16_t>(col * 65));  // 0 .. 4095
  ImageNotes notes;
  const cv::Mat gray = DecodeGrayImage(Encode(twelve_bit, ".png"), "ramp.png", &notes).value();
  ASSERT_EQ(gray.type(), CV_8UC1);
  EXPECT_EQ(gray.at<uint8_t>(0, 0), 0);
  EXPECT_EQ(gray.at<uint8_t>(0, 63), 255);  // the high byte alone would give 15
  EXPECT_NEAR(gray.at<uint8_t>(0, 32), 130, 1);
  EXPECT_EQ(notes.bits, 16);
  EXPECT_EQ(notes.range_high, 4095);
  EXPECT_THAT(DescribeImageNotes(notes), HasSubstr("16-bit, grey 0-4095 scaled to 0-255"));
}

TEST(ImageFileTest, AlphaIsCompositedOverWhite) {
  cv::Mat bgra(4, 3, CV_8UC4, cv::Scalar(0, 0, 0, 255));       // opaque black
  bgra.row(1).setTo(cv::Scalar(0, 0, 0, 0));                    // transparent black: the sheet
  bgra.row(2).setTo(cv::Scalar(0, 0, 0, 128));                  // half
  bgra.row(3).setTo(cv::Scalar(255, 255, 255, 255));            // opaque white
  ImageNotes notes;
  const cv::Mat gray = DecodeGrayImage(Encode(bgra, ".png"), "alpha.png", &notes).value();
  EXPECT_EQ(notes.channels, 4);
  EXPECT_EQ(gray.at<uint8_t>(0, 0), 0);
  EXPECT_EQ(gray.at<uint8_t>(1, 0), 255);
  EXPECT_NEAR(gray.at<uint8_t>(2, 0), 127, 1);
  EXPECT_EQ(gray.at<uint8_t>(3, 0), 255);
}

TEST(ImageFileTest, ColourBecomesWeightedGrey) {
  cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(0, 0, 255));  // pure red
  const cv::Mat gray = DecodeGrayImage(Encode(bgr, ".png"), "red.png").value();
  EXPECT_NEAR(gray.at<uint8_t>(0, 0), 76, 1);  // 0.299 · 255
}

TEST(ImageFileTest, ExifOrientationIsReportedNeverApplied) {
  cv::Mat wide(20, 40, CV_8UC1, cv::Scalar(200));
  wide.colRange(0, 10).setTo(0);  // dark on the left, as stored
  std::string jpeg = Encode(wide, ".jpg");
  jpeg.insert(2, ExifOrientationSegment(6));  // "rotate 90° clockwise to view"
  EXPECT_EQ(ReadImageHeader(jpeg).orientation, 6);
  ImageNotes notes;
  const cv::Mat gray = DecodeGrayImage(jpeg, "portrait.jpg", &notes).value();
  EXPECT_EQ(gray.cols, 40);  // pixels as stored: not turned into 20 × 40
  EXPECT_EQ(gray.rows, 20);
  EXPECT_LT(gray.at<uint8_t>(10, 2), 50);
  EXPECT_EQ(notes.orientation, 6);
  EXPECT_THAT(DescribeImageNotes(notes), HasSubstr("EXIF orientation 6 not applied"));
}

TEST(ImageFileTest, OrientationOutOfRangeOrMissingIsOne) {
  EXPECT_EQ(ReadTiffOrientation(""), 1);
  EXPECT_EQ(ReadTiffOrientation(ExifOrientationSegment(9).substr(10)), 1);
  EXPECT_EQ(ReadTiffOrientation(ExifOrientationSegment(3).substr(10)), 3);
  EXPECT_EQ(ReadTiffOrientation(ExifOrientationSegment(3).substr(10, 12)), 1);  // cut inside the entry
}

}  // namespace
}  // namespace hexcal

#include "vision/image_header.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/atomic_file.h"
#include "tests/test_support.h"
#include "vision/detection.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;
using ::testing::HasSubstr;

// A small grey gradient, so that a decoder has something to check.
cv::Mat Gradient(int width, int height) {
  cv::Mat image(height, width, CV_8U);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(3 * x + 5 * y);
  }
  return image;
}

std::string Encode(const cv::Mat& image, const std::string& extension) {
  std::vector<uint8_t> buffer;
  EXPECT_TRUE(cv::imencode(extension, image, buffer));
  return std::string(buffer.begin(), buffer.end());
}

void PutBigEndian(std::string* bytes, size_t offset, uint64_t value, int width) {
  for (int i = width - 1; i >= 0; --i, value >>= 8)
    (*bytes)[offset + static_cast<size_t>(i)] = static_cast<char>(value);
}

// CRC-32 of PNG chunks (ISO 3309, reflected polynomial 0xEDB88320).
uint32_t Crc32(std::string_view bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (char c : bytes) {
    crc ^= static_cast<uint8_t>(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A valid small PNG whose IHDR claims width x height, with its CRC recomputed:
// only the size is wrong, so only the size check can refuse it.
std::string PngClaiming(uint32_t width, uint32_t height) {
  std::string png = Encode(Gradient(8, 8), ".png");
  PutBigEndian(&png, 16, width, 4);
  PutBigEndian(&png, 20, height, 4);
  PutBigEndian(&png, 29, Crc32(std::string_view(png).substr(12, 17)), 4);
  return png;
}

// The same small image as a baseline JPEG, and as a progressive one (a scan
// per spectral band, DHT segments between scans) with a restart marker
// (FF D0-D7) after every MCU row.
std::vector<std::string> SmallJpegs() {
  std::vector<uint8_t> progressive;
  EXPECT_TRUE(cv::imencode(".jpg", Gradient(64, 48), progressive,
                           {cv::IMWRITE_JPEG_PROGRESSIVE, 1, cv::IMWRITE_JPEG_RST_INTERVAL, 1}));
  return {Encode(Gradient(64, 48), ".jpg"), std::string(progressive.begin(), progressive.end())};
}

// A small baseline JPEG whose frame header (SOF0) claims width x height.
std::string JpegClaiming(uint16_t width, uint16_t height) {
  std::string jpeg = Encode(Gradient(64, 48), ".jpg");
  const size_t sof = jpeg.find("\xFF\xC0");
  EXPECT_NE(sof, std::string::npos);
  PutBigEndian(&jpeg, sof + 5, height, 2);
  PutBigEndian(&jpeg, sof + 7, width, 2);
  return jpeg;
}

// An 8-bit grey uncompressed TIFF written by hand: byte order, classic or
// BigTIFF, and the type of ImageWidth/ImageLength (3 SHORT, 4 LONG, 16 LONG8).
struct TiffSpec {
  bool big_endian = false;
  bool bigtiff = false;
  int size_type = 3;
};

std::string HandMadeTiff(const TiffSpec& spec, const cv::Mat& image) {
  std::string tiff;
  auto put = [&](uint64_t value, int width) {
    for (int i = 0; i < width; ++i) {
      const int shift = 8 * (spec.big_endian ? width - 1 - i : i);
      tiff.push_back(static_cast<char>(value >> shift));
    }
  };
  const int offset_bytes = spec.bigtiff ? 8 : 4;
  tiff += spec.big_endian ? "MM" : "II";
  put(spec.bigtiff ? 43 : 42, 2);
  if (spec.bigtiff) {  // offset size, a zero word
    put(8, 2);
    put(0, 2);
  }
  put(spec.bigtiff ? 16 : 8, offset_bytes);  // the first IFD follows at once
  const uint64_t width = static_cast<uint64_t>(image.cols), height = static_cast<uint64_t>(image.rows);
  const int type_bytes = spec.size_type == 3 ? 2 : spec.size_type == 4 ? 4 : 8;
  const struct {
    int tag, type;
    uint64_t value;
  } entries[] = {{256, spec.size_type, width},
                 {257, spec.size_type, height},
                 {258, 3, 8},
                 {259, 3, 1},
                 {262, 3, 1},
                 {273, 4, 0},  // StripOffsets: filled in below
                 {277, 3, 1},
                 {278, 4, height},
                 {279, 4, width * height}};
  const uint64_t entry_count = std::size(entries);
  const uint64_t data_offset =
      tiff.size() + (spec.bigtiff ? 8 : 2) + entry_count * (4 + 2 * offset_bytes) + offset_bytes;
  put(entry_count, spec.bigtiff ? 8 : 2);
  for (const auto& entry : entries) {
    const int bytes = entry.type == 3 ? 2 : entry.type == 4 ? 4 : type_bytes;
    put(static_cast<uint64_t>(entry.tag), 2);
    put(static_cast<uint64_t>(entry.type), 2);
    put(1, offset_bytes);
    put(entry.tag == 273 ? data_offset : entry.value, bytes);  // left-justified in the value field
    tiff.append(static_cast<size_t>(offset_bytes - bytes), '\0');
  }
  put(0, offset_bytes);  // no next IFD
  tiff.append(reinterpret_cast<const char*>(image.data), image.total());
  return tiff;
}

TEST(ImageHeaderTest, PngSizeIsReadFromIhdr) {
  const std::optional<PixelSize> size = ReadPngSize(Encode(Gradient(37, 21), ".png"));
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 37u);
  EXPECT_EQ(size->height, 21u);
  EXPECT_FALSE(ReadPngSize(std::string("\x89PNG\r\n\x1a\n", 8)).has_value());
}

TEST(ImageHeaderTest, APngClaimingAHugeSizeIsRefusedBeforeDecoding) {
  const std::string png = PngClaiming(30000, 30000);
  ASSERT_EQ(ReadPngSize(png)->Pixels(), 900'000'000u);
  StatusOr<cv::Mat> image = DecodeGrayImage(png, "huge.png");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().message(), "huge.png: 30000 x 30000 pixels is over the 150-megapixel limit");
}

TEST(ImageHeaderTest, TheLimitLetsRealImagesThrough) {
  EXPECT_LE((PixelSize{12000, 9000}).Pixels(), kMaxImagePixels);  // a 108-MP phone photo
  EXPECT_LE((PixelSize{10482, 8268}).Pixels(), kMaxImagePixels);  // the print-resolution chart
  EXPECT_GT((PixelSize{15000, 10001}).Pixels(), kMaxImagePixels);
  EXPECT_EQ((PixelSize{uint64_t{1} << 40, uint64_t{1} << 40}).Pixels(), std::numeric_limits<uint64_t>::max());
}

TEST(ImageHeaderTest, ThePrintResolutionChartStillDecodes) {
  const std::filesystem::path chart = SourceDir() / "../shared/real-images/aprilgrid-borders/t36h11_1bit_margin.png";
  if (!std::filesystem::exists(chart)) GTEST_SKIP() << chart << " is not on this machine";
  StatusOr<cv::Mat> image = LoadGrayImage(chart.string());
  ASSERT_TRUE(image.ok()) << image.status().message();
  EXPECT_EQ(image->cols, 10482);
  EXPECT_EQ(image->rows, 8268);
}

TEST(ImageHeaderTest, JpegWalkReadsTheFrameHeaderAndFindsTheEnd) {
  for (const std::string& jpeg : SmallJpegs()) {
    const JpegLayout layout = WalkJpeg(jpeg);
    EXPECT_TRUE(layout.complete);
    EXPECT_EQ(layout.corrupt, "");
    EXPECT_EQ(layout.end, jpeg.size());
    ASSERT_TRUE(layout.size.has_value());
    EXPECT_EQ(layout.size->width, 64u);
    EXPECT_EQ(layout.size->height, 48u);
  }
}

TEST(ImageHeaderTest, AJpegClaimingAHugeSizeIsRefusedBeforeDecoding) {
  // Under OpenCV's own limit (2^30 pixels), which alone would let it through.
  StatusOr<cv::Mat> image = DecodeGrayImage(JpegClaiming(30000, 30000), "huge.jpg");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().message(), "huge.jpg: 30000 x 30000 pixels is over the 150-megapixel limit");
}

TEST(ImageHeaderTest, AJpegWithDataAfterItsEndOfImageDecodes) {
  const std::string primary = Encode(Gradient(64, 48), ".jpg");
  // As phones append a gain map or MPF images (a second JPEG) and trailers of
  // their own, longer than the 64 bytes in which the old check sought an EOI.
  const std::string file = primary + Encode(Gradient(16, 12), ".jpg") + "\xFF\xD8" + std::string(100, 'x');
  EXPECT_EQ(WalkJpeg(file).end, primary.size());
  StatusOr<cv::Mat> image = DecodeGrayImage(file, "phone.jpg");
  ASSERT_TRUE(image.ok()) << image.status().message();
  EXPECT_EQ(image->cols, 64);
}

TEST(ImageHeaderTest, AJpegCutAnywhereIsTruncated) {
  for (const std::string& jpeg : SmallJpegs()) {
    // From SOI and a marker's FF on, the file is a JPEG.
    for (size_t cut = 3; cut < jpeg.size(); ++cut) {
      const ImageHeader header = ReadImageHeader(std::string_view(jpeg).substr(0, cut));
      ASSERT_TRUE(header.truncated) << "cut at " << cut;
    }
  }
  const std::string jpeg = Encode(Gradient(64, 48), ".jpg");
  const size_t scan = jpeg.find("\xFF\xDA");
  ASSERT_NE(scan, std::string::npos);
  StatusOr<cv::Mat> image = DecodeGrayImage(jpeg.substr(0, (scan + jpeg.size()) / 2), "cut.jpg");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().message(), "cut.jpg: truncated JPEG (no end-of-image marker)");
}

TEST(ImageHeaderTest, AnExifThumbnailsEndOfImageIsNotThePrimarys) {
  const std::string primary = Encode(Gradient(64, 48), ".jpg");
  const std::string thumbnail = Encode(Gradient(8, 6), ".jpg");
  std::string app1 = "\xFF\xE1..Exif" + std::string(2, '\0') + thumbnail;
  PutBigEndian(&app1, 2, app1.size() - 2, 2);
  const std::string file = primary.substr(0, 2) + app1 + primary.substr(2);
  const JpegLayout layout = WalkJpeg(file);
  EXPECT_TRUE(layout.complete);
  EXPECT_EQ(layout.size->width, 64u);
  // Cut in the primary's scan, the file still holds the thumbnail's EOI.
  const std::string cut = file.substr(0, file.size() - 100);
  ASSERT_NE(cut.find("\xFF\xD9"), std::string::npos);
  EXPECT_THAT(DecodeGrayImage(cut, "cut.jpg").status().message(), HasSubstr("truncated JPEG"));
  StatusOr<cv::Mat> image = DecodeGrayImage(file, "exif.jpg");
  ASSERT_TRUE(image.ok()) << image.status().message();
  EXPECT_EQ(image->cols, 64);
}

TEST(ImageHeaderTest, AJpegWithAnImpossibleSegmentIsCorrupt) {
  std::string jpeg = Encode(Gradient(64, 48), ".jpg");
  PutBigEndian(&jpeg, 4, 1, 2);  // APP0's length
  StatusOr<cv::Mat> image = DecodeGrayImage(jpeg, "bad.jpg");
  ASSERT_FALSE(image.ok());
  EXPECT_EQ(image.status().message(), "bad.jpg: cannot decode: corrupt JPEG (marker FFE0 at byte 2 has length 1)");
}

// Issue 12: the Pixel's JPEG (EXIF, JFIF and ICC segments before the frame).
TEST(ImageHeaderTest, APhoneJpegDecodesWithOrWithoutAGainMapAppended) {
  const std::string path = (SourceDir() / "tests/data/real/t36h11_2bit_margin.jpg").string();
  StatusOr<std::string> bytes = ReadFileToString(path, kMaxImageBytes);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  const JpegLayout layout = WalkJpeg(*bytes);
  ASSERT_TRUE(layout.complete);
  EXPECT_EQ(layout.size->width, 3072u);
  EXPECT_EQ(layout.size->height, 4080u);
  // Ultra HDR appends a gain map (a JPEG); some phones then add a trailer.
  const std::string with_gain_map = *bytes + Encode(Gradient(768, 1020), ".jpg") + std::string(100, '\0');
  for (const std::string& file : {*bytes, with_gain_map}) {
    StatusOr<cv::Mat> image = DecodeGrayImage(file, "pixel.jpg");
    ASSERT_TRUE(image.ok()) << image.status().message();
    EXPECT_EQ(image->total(), 3072u * 4080u);
  }
}

class TiffSizeTest : public ::testing::TestWithParam<TiffSpec> {};

TEST_P(TiffSizeTest, IsReadAndTheImageDecodes) {
  const cv::Mat gradient = Gradient(40, 30);
  const std::string tiff = HandMadeTiff(GetParam(), gradient);
  const std::optional<PixelSize> size = ReadTiffSize(tiff);
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 40u);
  EXPECT_EQ(size->height, 30u);
  StatusOr<cv::Mat> image = DecodeGrayImage(tiff, "view.tif");
  ASSERT_TRUE(image.ok()) << image.status().message();
  EXPECT_EQ(cv::norm(*image, gradient, cv::NORM_INF), 0);
}

INSTANTIATE_TEST_SUITE_P(ByteOrdersAndTypes, TiffSizeTest,
                         ::testing::Values(TiffSpec{false, false, 3}, TiffSpec{true, false, 3},
                                           TiffSpec{false, false, 4}, TiffSpec{true, false, 4},
                                           TiffSpec{false, true, 16}, TiffSpec{true, true, 16}));

TEST(ImageHeaderTest, OpenCvsTiffSizeIsRead) {
  const std::optional<PixelSize> size = ReadTiffSize(Encode(Gradient(33, 17), ".tiff"));
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->width, 33u);
  EXPECT_EQ(size->height, 17u);
}

TEST(ImageHeaderTest, ATiffClaimingAHugeSizeIsRefused) {
  std::string tiff = HandMadeTiff(TiffSpec{true, false, 4}, Gradient(4, 4));
  const size_t width_value = 8 + 2 + 8;  // the first entry's value field; ImageLength's is 12 bytes on
  PutBigEndian(&tiff, width_value, 40000, 4);
  PutBigEndian(&tiff, width_value + 12, 5000, 4);
  EXPECT_EQ(DecodeGrayImage(tiff, "huge.tif").status().message(),
            "huge.tif: 40000 x 5000 pixels is over the 150-megapixel limit");
}

// Offsets and counts are the file's word: none of them may take a read
// outside it (ASan checks this in `make sanitize`).
TEST(ImageHeaderTest, LyingOffsetsAndCountsStayInsideTheFile) {
  std::string tiff = HandMadeTiff(TiffSpec{false, false, 3}, Gradient(4, 4));
  tiff[8] = '\xFF', tiff[9] = '\xFF';  // 65535 IFD entries
  EXPECT_TRUE(ReadTiffSize(tiff).has_value());
  tiff[4] = '\xF0';  // the first IFD far past the end
  EXPECT_FALSE(ReadTiffSize(tiff).has_value());
  const std::string files[] = {Encode(Gradient(20, 10), ".png"), Encode(Gradient(20, 10), ".jpg"),
                               HandMadeTiff(TiffSpec{true, true, 16}, Gradient(20, 10))};
  for (const std::string& file : files) {
    for (size_t cut = 0; cut < file.size(); ++cut) ReadImageHeader(std::string_view(file).substr(0, cut));
  }
}

}  // namespace
}  // namespace hexcal

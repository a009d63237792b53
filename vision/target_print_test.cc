#include "vision/target_print.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "core/atomic_file.h"
#include "tests/test_support.h"
#include "vision/detection.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::testing::HasSubstr;

TEST(TargetPrintTest, PdfIsWellFormedAndOnA3) {
  const std::string pdf = TargetPdf(DefaultTarget());
  ASSERT_EQ(pdf.rfind("%PDF-1.6\n", 0), 0u);
  EXPECT_THAT(pdf, HasSubstr("/MediaBox [0 0 841.890 1190.551]"));  // A3 portrait, 297 x 420 mm
  EXPECT_EQ(DescribeSheet(TargetPdfSheet(DefaultTarget())), "A3 portrait (297 x 420 mm)");  // what `print` says
  EXPECT_THAT(pdf, HasSubstr("/PrintScaling /None"));
  EXPECT_THAT(pdf, HasSubstr("(hexcal target: 6 x 6 tag36h11, tag 30 mm"));
  // Every xref offset points at its object, and startxref at the table.
  const size_t xref = pdf.find("\nxref\n") + 1;
  const std::smatch::size_type start = std::stoul(pdf.substr(pdf.rfind("startxref\n") + 10));
  EXPECT_EQ(start, xref);
  std::istringstream table(pdf.substr(xref));
  std::string line;
  std::getline(table, line);  // xref
  std::getline(table, line);  // 0 N
  const int count = std::stoi(line.substr(2));
  std::getline(table, line);  // free entry
  for (int object = 1; object < count; ++object) {
    std::getline(table, line);
    ASSERT_EQ(line.size(), 19u) << line;  // 20 bytes with the newline
    const size_t offset = std::stoul(line.substr(0, 10));
    EXPECT_EQ(pdf.compare(offset, std::to_string(object).size() + 6, std::to_string(object) + " 0 obj"), 0) << object;
  }
  // The content stream's /Length is its byte count.
  const std::regex length_re("/Length (\\d+) >>\nstream\n");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(pdf, match, length_re));
  const size_t stream_start = static_cast<size_t>(match.position(0) + match.length(0));
  EXPECT_EQ(pdf.compare(stream_start + std::stoul(match[1]), 9, "endstream"), 0);
}

TEST(TargetPrintTest, PngIsToScaleAndDecodesAsTheTarget) {
  const Target target = DefaultTarget();
  const double dpi = 120;
  StatusOr<std::string> png = TargetPng(target, dpi);
  ASSERT_TRUE(png.ok()) << png.status().message();
  // pHYs: 120 dpi = 4724 pixels per metre.
  const size_t phys = png->find("pHYs");
  ASSERT_NE(phys, std::string::npos);
  const auto byte = [&](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>((*png)[i])); };
  EXPECT_EQ(byte(phys + 4) << 24 | byte(phys + 5) << 16 | byte(phys + 6) << 8 | byte(phys + 7), 4724u);
  cv::Mat image = cv::imdecode(std::vector<uint8_t>(png->begin(), png->end()), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(image.empty());
  // Sheet 243 mm, page margins 2 × 10 mm.
  EXPECT_EQ(image.cols, static_cast<int>(std::ceil(263 * dpi / 25.4)));

  // As a camera sees the print: the edge fit models optical blur (docs/vision.md).
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8);
  std::unique_ptr<TagDetector> detector = TagDetector::Create(DetectorOptions{}).value();
  const Detections found = detector->Detect(image);
  ASSERT_EQ(found.tags.size(), 36u);
  const double px_per_mm = dpi / 25.4;
  const auto& tag0 = found.tags[0].corners;
  // AprilTag order on the page: bottom-left, bottom-right, top-right, top-left.
  EXPECT_LT(tag0[0].x(), tag0[1].x());
  EXPECT_GT(tag0[0].y(), tag0[3].y());
  EXPECT_NEAR((tag0[1] - tag0[0]).norm(), 30 * px_per_mm, 0.1);
  // Tag 1 is to the right of tag 0, tag 6 above it, one pitch (39 mm) away.
  EXPECT_NEAR((found.tags[1].corners[0] - tag0[0]).x(), 39 * px_per_mm, 0.1);
  EXPECT_NEAR((found.tags[6].corners[0] - tag0[0]).y(), -39 * px_per_mm, 0.1);
  // Tag 0's bottom-left corner sits 10 mm + 9 mm margin from the page's left edge.
  EXPECT_NEAR(tag0[0].x() + 0.5, 19 * px_per_mm, 0.1);
}

// Kalibr's two-cell border, printed and read back: every tag decodes with
// border_bits 2 and none with 1 reads as a wrong id.
TEST(TargetPrintTest, TwoCellBordersPrintAndDetect) {
  Target kalibr = DefaultTarget();
  kalibr.border_bits = 2;
  const StatusOr<std::string> png = TargetPng(kalibr, 150);
  ASSERT_TRUE(png.ok()) << png.status().message();
  cv::Mat image = cv::imdecode(std::vector<uint8_t>(png->begin(), png->end()), cv::IMREAD_GRAYSCALE);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8);
  const Detections found = TagDetector::Create(ForTarget(DetectorOptions{}, kalibr)).value()->Detect(image);
  ASSERT_EQ(found.tags.size(), 36u);
  for (size_t i = 0; i < found.tags.size(); ++i) EXPECT_EQ(found.tags[i].id, static_cast<int>(i));
  // The black square is still tag_size: 30 mm between corners 0 and 1.
  EXPECT_NEAR((found.tags[0].corners[1] - found.tags[0].corners[0]).norm(), 30 * 150 / 25.4, 0.15);
  const Detections one_cell = TagDetector::Create(DetectorOptions{}).value()->Detect(image);
  EXPECT_LT(one_cell.tags.size(), 36u);
}

TEST(TargetPrintTest, WritesByExtensionAndRejectsOthers) {
  TempDir dir;
  EXPECT_TRUE(WriteTargetPrint(DefaultTarget(), dir.File("t.PDF"), 300).ok());
  EXPECT_TRUE(ReadFileToString(dir.File("t.PDF"))->rfind("%PDF", 0) == 0);
  EXPECT_THAT(WriteTargetPrint(DefaultTarget(), dir.File("t.svg"), 300).message(),
              HasSubstr("must end in .pdf or .png"));
  EXPECT_THAT(TargetPng(DefaultTarget(), 5000).status().message(),
              HasSubstr("dpi: must be at most 1200 dpi, got 5000"));
}

}  // namespace
}  // namespace hexcal

#include "vision/measure.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "tests/test_support.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

TEST(MeasureTest, EveryFileGetsAStatusAndTheBatchCarriesOn) {
  TempDir dir;
  const Camera camera = SimulatedCamera();
  const Target target = DefaultTarget();
  const Renderer renderer(camera, target, RenderOptions{});
  const std::vector<Pose> poses = RandomViewPoses(target, 2, 400, 600, 30, 20, 0.1, 4);
  cv::imwrite(dir.File("a_view.png"), renderer.Render(poses[0], 0).image);
  cv::imwrite(dir.File("b_view.JPG"), renderer.Render(poses[1], 1).image, {cv::IMWRITE_JPEG_QUALITY, 98});
  WriteTextFile(dir.File("c_empty.png"), "");
  std::vector<uint8_t> png;
  cv::imencode(".png", renderer.Render(poses[0], 2).image, png);
  WriteTextFile(dir.File("d_truncated.png"), std::string(png.begin(), png.begin() + 200));
  cv::imwrite(dir.File("e_blank.tiff"), cv::Mat(768, 1024, CV_8U, cv::Scalar(120)));
  cv::imwrite(dir.File("f_small.png"), cv::Mat(480, 640, CV_8U, cv::Scalar(120)));
  WriteTextFile(dir.File("notes.txt"), "not an image");

  StatusOr<std::vector<std::string>> files = ListImages(dir.path().string());
  ASSERT_TRUE(files.ok()) << files.status().message();
  ASSERT_EQ(files->size(), 6u);  // notes.txt is not an image
  std::atomic<int> calls{0};
  StatusOr<std::vector<ImageMeasurement>> rows =
      MeasureImages(*files, camera, target, MeasureOptions{}, {[&](int, int total) {
        EXPECT_EQ(total, 6);
        ++calls;
      }});
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  EXPECT_EQ(calls.load(), 6);
  const std::vector<PoseStatus> expected = {PoseStatus::kOk,         PoseStatus::kOk,       PoseStatus::kUnreadable,
                                            PoseStatus::kUnreadable, PoseStatus::kNoTarget, PoseStatus::kWrongSize};
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ((*rows)[i].pose.status, expected[i]) << (*rows)[i].file << ": " << (*rows)[i].pose.message;
  }
  EXPECT_THAT((*rows)[2].pose.message, HasSubstr("empty file"));
  EXPECT_THAT((*rows)[3].pose.message, HasSubstr("truncated PNG"));
  EXPECT_THAT((*rows)[5].pose.message, HasSubstr("image is 640 x 480, the camera 1024 x 768"));
  EXPECT_LT(((*rows)[0].pose.camera_from_target.position - poses[0].position).norm(), 0.1);
  EXPECT_LT(((*rows)[1].pose.camera_from_target.position - poses[1].position).norm(), 0.2);

  const std::string out = dir.File("camera_poses.csv");
  ASSERT_TRUE(WriteImageMeasurementsCsv(out, *rows).ok());
  StatusOr<CsvTable> table = ReadCsv(out);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(table->header, ImageMeasurementColumns());
  ASSERT_EQ(table->rows.size(), 6u);
  EXPECT_EQ(table->rows[0][15], "ok");
  EXPECT_EQ(table->rows[2][15], "unreadable");
  EXPECT_EQ(table->rows[2][1], "");  // no pose
  EXPECT_NEAR(*NumberAt(*table, 0, 3), poses[0].position.z(), 0.1);
  // The covariance comes back whole from the σ and correlation columns.
  ASSERT_EQ(table->header.size(), 32u);
  StatusOr<std::string> text = ReadFileToString(out);
  ASSERT_TRUE(text.ok());
  StatusOr<std::vector<ImageMeasurementRecord>> records = ParseImageMeasurementsCsv(*text, out);
  ASSERT_TRUE(records.ok()) << records.status().message();
  ASSERT_EQ(records->size(), 6u);
  for (size_t i : {0u, 1u}) {
    const ImageMeasurementRecord& record = (*records)[i];
    ASSERT_TRUE(record.ok);
    const Matrix6d& expected = (*rows)[i].pose.covariance_vector;
    EXPECT_LT((record.covariance - expected).norm(), 1e-12 * expected.norm()) << record.file;
    EXPECT_LT((record.camera_from_target.position - (*rows)[i].pose.camera_from_target.position).norm(), 1e-9);
  }
  EXPECT_FALSE((*records)[2].ok);
  EXPECT_EQ((*records)[2].cells, table->rows[2]);
  EXPECT_EQ(table->rows[2][17], "");
}

TEST(MeasureTest, CovarianceFromColumnsRejectsBadValues) {
  std::array<double, 6> sigma = {1, 2, 3, 4, 5, 6};
  std::array<double, 15> correlation{};
  correlation[0] = 0.5;
  const std::optional<Matrix6d> covariance = CovarianceFromSigmasAndCorrelations(sigma, correlation);
  ASSERT_TRUE(covariance.has_value());
  EXPECT_DOUBLE_EQ((*covariance)(0, 1), 1.0);
  EXPECT_DOUBLE_EQ((*covariance)(5, 5), 36.0);
  correlation[3] = 1.5;
  EXPECT_FALSE(CovarianceFromSigmasAndCorrelations(sigma, correlation).has_value());
  correlation[3] = 0;
  sigma[2] = -1;
  EXPECT_FALSE(CovarianceFromSigmasAndCorrelations(sigma, correlation).has_value());
  sigma[2] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(CovarianceFromSigmasAndCorrelations(sigma, correlation).has_value());
}

TEST(MeasureTest, ListImagesErrors) {
  TempDir dir;
  EXPECT_THAT(ListImages(dir.File("missing")).status().message(), HasSubstr("no such file or folder"));
  EXPECT_THAT(ListImages(dir.path().string()).status().message(), HasSubstr("no PNG, JPEG or TIFF images"));
  WriteTextFile(dir.File("one.png"), "");
  StatusOr<std::vector<std::string>> one = ListImages(dir.File("one.png"));
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(one->size(), 1u);
}

}  // namespace
}  // namespace hexcal

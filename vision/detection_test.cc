#include "vision/detection.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "tests/test_support.h"
#include "vision/edge_refine.h"
#include "vision/renderer.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

struct CornerErrors {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double rms = 0;
  int count = 0;
};

CornerErrors Compare(const Detections& detections, const RenderedView& view) {
  std::map<std::pair<int, int>, Eigen::Vector2d> truth;
  for (const ProjectedCorner& c : view.corners) truth[{c.tag_id, c.corner}] = c.pixel;
  CornerErrors errors;
  double sum2 = 0;
  for (const TagDetection& tag : detections.tags) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d e = tag.corners[static_cast<size_t>(k)] - truth.at({tag.id, k});
      errors.mean += e;
      sum2 += e.squaredNorm();
      ++errors.count;
    }
  }
  errors.mean /= errors.count;
  errors.rms = std::sqrt(sum2 / errors.count);
  return errors;
}

class DetectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::vector<Pose> poses = RandomViewPoses(target_, 3, 450, 550, 30, 20, 0.1, 21);
    const Renderer renderer(camera_, target_, RenderOptions{});
    for (size_t i = 0; i < poses.size(); ++i) views_.push_back(renderer.Render(poses[i], i));
  }
  Target target_ = DefaultTarget();
  Camera camera_ = SimulatedCamera();
  std::vector<RenderedView> views_;
};

TEST_F(DetectionTest, LibraryCornersAreShiftedToOpenCvPixelCentres) {
  DetectorOptions options;
  options.refine_edges = false;
  std::unique_ptr<TagDetector> detector = TagDetector::Create(options).value();
  for (const RenderedView& view : views_) {
    const Detections found = detector->Detect(view.image);
    ASSERT_EQ(found.tags.size(), 36u);
    const CornerErrors errors = Compare(found, view);
    // Unshifted, the library's corners would be 0.5 px off in both axes, and
    // without UndoWhiteGrowth about 0.7 px inwards. The quad fit on the grown
    // image scatters by 0.3 px: the edge fit starts from there.
    EXPECT_LT(errors.mean.cwiseAbs().maxCoeff(), 0.05);
    EXPECT_LT(errors.rms, 0.35);
    for (const TagDetection& tag : found.tags) EXPECT_FALSE(tag.refined);
  }
}

TEST_F(DetectionTest, EdgeFitInTheUndistortedImageIsAccurate) {
  auto ideal = std::make_shared<const IdealPixelMap>(camera_);
  std::unique_ptr<TagDetector> undistorted = TagDetector::Create(DetectorOptions{}, ideal).value();
  std::unique_ptr<TagDetector> raw = TagDetector::Create(DetectorOptions{}).value();
  for (const RenderedView& view : views_) {
    const Detections found = undistorted->Detect(view.image);
    ASSERT_EQ(found.tags.size(), 36u);
    for (const TagDetection& tag : found.tags) EXPECT_TRUE(tag.refined) << tag.id;
    const CornerErrors errors = Compare(found, view);
    EXPECT_LT(errors.mean.cwiseAbs().maxCoeff(), 0.005);
    EXPECT_LT(errors.rms, 0.035);
    // Straight-line fits in the distorted image are biased by the curvature.
    EXPECT_GT(Compare(raw->Detect(view.image), view).rms, errors.rms);
  }
}

// Kalibr's two-cell border: the quad is the outer edge of the thicker
// border, the data cells sit one cell further in.
TEST_F(DetectionTest, TwoCellBordersDecodeWithTheirCornersInOrder) {
  Target kalibr = target_;
  kalibr.border_bits = 2;
  const std::vector<Pose> poses = RandomViewPoses(kalibr, 2, 450, 550, 30, 20, 0.1, 5);
  const Renderer renderer(camera_, kalibr, RenderOptions{});
  auto ideal = std::make_shared<const IdealPixelMap>(camera_);
  DetectorOptions two = ForTarget(DetectorOptions{}, kalibr);
  ASSERT_EQ(two.border_bits, 2);
  std::unique_ptr<TagDetector> detector = TagDetector::Create(two, ideal).value();
  std::unique_ptr<TagDetector> one_cell = TagDetector::Create(DetectorOptions{}, ideal).value();
  for (size_t i = 0; i < poses.size(); ++i) {
    const RenderedView view = renderer.Render(poses[i], i);
    const Detections found = detector->Detect(view.image);
    ASSERT_EQ(found.tags.size(), 36u);
    const CornerErrors errors = Compare(found, view);  // truth by id and corner: the order is checked too
    EXPECT_LT(errors.rms, 0.035);
    for (const TagDetection& tag : found.tags) EXPECT_TRUE(tag.refined) << tag.id;
    // Read with one border cell, the data are shifted by a cell: no tag, or
    // (where rows happen to repeat) the right one at the right place.
    const Detections wrong = one_cell->Detect(view.image);
    EXPECT_LT(wrong.tags.size(), 36u);
    if (!wrong.tags.empty()) {
      EXPECT_LT(Compare(wrong, view).rms, 0.5);
    }
  }
}

TEST_F(DetectionTest, CornerCovarianceDescribesTheErrors) {
  auto ideal = std::make_shared<const IdealPixelMap>(camera_);
  std::unique_ptr<TagDetector> detector = TagDetector::Create(DetectorOptions{}, ideal).value();
  // Mean of eᵀ C⁻¹ e over tags is 8 (χ² with 8 degrees of freedom) when C is right.
  double sum = 0;
  int tags = 0;
  for (const RenderedView& view : views_) {
    std::map<std::pair<int, int>, Eigen::Vector2d> truth;
    for (const ProjectedCorner& c : view.corners) truth[{c.tag_id, c.corner}] = c.pixel;
    for (const TagDetection& tag : detector->Detect(view.image).tags) {
      Eigen::Matrix<double, 8, 1> e;
      for (int k = 0; k < 4; ++k) e.segment<2>(2 * k) = tag.corners[static_cast<size_t>(k)] - truth.at({tag.id, k});
      sum += e.dot(tag.covariance.ldlt().solve(e));
      ++tags;
    }
  }
  const double mean = sum / tags;
  std::cout << "corner NEES per tag " << mean << " (8 expected) over " << tags << " tags\n";
  EXPECT_GT(mean, 4);
  EXPECT_LT(mean, 16);
}

TEST_F(DetectionTest, WeakAndCorrectedDecodesAreRejected) {
  DetectorOptions strict;
  strict.min_decision_margin = 1000;
  std::unique_ptr<TagDetector> detector = TagDetector::Create(strict).value();
  const Detections found = detector->Detect(views_[0].image);
  EXPECT_TRUE(found.tags.empty());
  ASSERT_EQ(found.rejected.size(), 36u);
  EXPECT_THAT(found.rejected[0].reason, HasSubstr("decision margin"));
  EXPECT_THAT(found.rejected[0].reason, HasSubstr("< 1e+03"));

  // Flip one data bit of tag 0 in a clean fronto-parallel view: one corrected bit.
  Camera pinhole = camera_;
  pinhole.distortion = {0, 0, 0, 0, 0};
  Pose pose;
  pose.rotation = Eigen::Vector3d(1, -1, -1).asDiagonal();
  pose.position = Eigen::Vector3d(0, 0, 500) - pose.rotation * Eigen::Vector3d(112.5, 112.5, 0);
  RenderedView view = Renderer(pinhole, target_, RenderOptions{}).Render(pose, 0);
  const double cell = target_.tag_size / 8;
  const TagCells cells = TagCellsOf("tag36h11", 0, 1)[0];
  // Cell (row 2, col 2) of the 10 × 10 grid: inside the data area.
  const Eigen::Vector2d lo = pinhole.Project(pose * Eigen::Vector3d(1 * cell, target_.tag_size - 1 * cell, 0));
  const Eigen::Vector2d hi = pinhole.Project(pose * Eigen::Vector3d(2 * cell, target_.tag_size - 2 * cell, 0));
  const uint8_t flipped = cells.IsBlack(2, 2) ? 200 : 30;
  cv::rectangle(view.image, cv::Point(static_cast<int>(std::ceil(lo.x())), static_cast<int>(std::ceil(lo.y()))),
                cv::Point(static_cast<int>(std::floor(hi.x())), static_cast<int>(std::floor(hi.y()))),
                cv::Scalar(flipped), cv::FILLED);
  std::unique_ptr<TagDetector> exact = TagDetector::Create(DetectorOptions{}).value();
  const Detections without = exact->Detect(view.image);
  EXPECT_EQ(without.tags.size(), 35u);
  ASSERT_EQ(without.rejected.size(), 1u);
  EXPECT_EQ(without.rejected[0].id, 0);
  EXPECT_EQ(without.rejected[0].reason, "1 corrected bits > 0");
  DetectorOptions tolerant;
  tolerant.max_hamming = 1;
  const Detections with = TagDetector::Create(tolerant).value()->Detect(view.image);
  EXPECT_EQ(with.tags.size(), 36u);
  EXPECT_EQ(with.tags[0].hamming, 1);
}

TEST_F(DetectionTest, MatchingDropsForeignAndDuplicateTags) {
  Detections detections;
  for (int id : {3, 4, 4, 40}) {
    TagDetection tag;
    tag.id = id;
    detections.tags.push_back(tag);
  }
  Target target = target_;
  target.rows = target.cols = 5;  // ids 0..24
  const BoardObservation observation = MatchToTarget(target, detections);
  EXPECT_EQ(observation.tag_ids, std::vector<int>{3});
  EXPECT_EQ(observation.foreign_tags, 1);
  EXPECT_EQ(observation.duplicate_tags, 2);
  ASSERT_EQ(observation.target_points.size(), 4u);
  EXPECT_TRUE(testing::MatrixNear(observation.target_points[0], target.TagCorners(3)[0], 0));
  EXPECT_EQ(observation.corner_covariances.size(), 1u);
}

TEST(LoadGrayImageTest, ErrorsNameTheFile) {
  TempDir dir;
  WriteTextFile(dir.File("empty.png"), "");
  WriteTextFile(dir.File("corrupt.png"), "\x89PNG\r\n\x1a\nthis is not a png");
  StatusOr<cv::Mat> empty = LoadGrayImage(dir.File("empty.png"));
  ASSERT_FALSE(empty.ok());
  EXPECT_THAT(empty.status().message(), HasSubstr("empty.png: empty file"));
  StatusOr<cv::Mat> corrupt = LoadGrayImage(dir.File("corrupt.png"));
  ASSERT_FALSE(corrupt.ok());
  EXPECT_THAT(corrupt.status().message(), HasSubstr("corrupt.png: truncated PNG"));
  WriteTextFile(dir.File("text.png"), "plain text, no image");
  EXPECT_THAT(LoadGrayImage(dir.File("text.png")).status().message(), HasSubstr("text.png: cannot decode"));
  EXPECT_THAT(LoadGrayImage(dir.File("missing.png")).status().message(), HasSubstr("no such file"));
}

TEST(DetectorOptionsTest, AreValidated) {
  DetectorOptions options;
  options.max_hamming = 3;
  StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(options);
  ASSERT_FALSE(detector.ok());
  EXPECT_THAT(detector.status().message(), HasSubstr("max_hamming"));
  options = DetectorOptions{};
  options.family = "tagCircle21h7";
  EXPECT_FALSE(TagDetector::Create(options).ok());
}

}  // namespace
}  // namespace hexcal

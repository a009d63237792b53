// Boards whose ids are not one contiguous grid, end to end: rendered and
// detected back, printed and detected back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "tests/test_support.h"
#include "vision/board_pose.h"
#include "vision/detection.h"
#include "vision/renderer.h"
#include "vision/target_print.h"

namespace hexcal {
namespace {

// Ids in no row-major order, with a hole.
const char* kIdMatrix =
    "tag_size: 30\ntag_spacing: 0.3\nlength_unit: mm\nids:\n"
    "  - [17, 200, 5, 93]\n  - [311, -1, 42, 8]\n  - [150, 61, 499, 2]\n";
// Not a grid at all: tags at their own places, one of them below and left of the first.
const char* kTagList =
    "tag_size: 30\nlength_unit: mm\ntags:\n"
    "  - {id: 17, x: 0, y: 0}\n  - {id: 200, x: 45, y: 8}\n  - {id: 5, x: 95, y: -12}\n"
    "  - {id: 93, x: 12, y: 50}\n  - {id: 311, x: 70, y: 62}\n  - {id: 42, x: 135, y: 30}\n"
    "  - {id: 8, x: -45, y: 85}\n  - {id: 150, x: -38, y: 20}\n";

Target Parse(const char* yaml) {
  StatusOr<Target> target = ParseTargetYaml(yaml, "test");
  EXPECT_TRUE(target.ok()) << target.status().message();
  return target.ok() ? *target : DefaultTarget();
}

// Renders `target` from a few poses and detects it: every tag whose corners
// are all in view is found, with its id, at the rendered truth, and the
// board's pose follows.
void ExpectRenderedTagsDetectedInTheTargetsGeometry(const Target& target) {
  const Camera camera = SimulatedCamera();
  const Renderer renderer(camera, target, RenderOptions{});
  auto ideal = std::make_shared<const IdealPixelMap>(camera);
  std::unique_ptr<TagDetector> detector = TagDetector::Create(ForTarget(DetectorOptions{}, target), ideal).value();
  const std::vector<Pose> poses = RandomViewPoses(target, 3, 400, 550, 30, 20, 0.1, 7);
  for (size_t i = 0; i < poses.size(); ++i) {
    const RenderedView view = renderer.Render(poses[i], i);
    std::map<std::pair<int, int>, Eigen::Vector2d> truth;
    std::map<int, int> visible_corners;
    for (const ProjectedCorner& c : view.corners) {
      truth[{c.tag_id, c.corner}] = c.pixel;
      visible_corners[c.tag_id] += c.visible;
    }
    std::set<int> expected, found;
    for (const auto& [id, count] : visible_corners) {
      if (count == 4) expected.insert(id);
    }
    const Detections detections = detector->Detect(view.image);
    double sum2 = 0;
    for (const TagDetection& tag : detections.tags) {
      found.insert(tag.id);
      ASSERT_TRUE(target.IndexOf(tag.id).has_value()) << tag.id;
      for (int k = 0; k < 4; ++k) sum2 += (tag.corners[static_cast<size_t>(k)] - truth.at({tag.id, k})).squaredNorm();
    }
    EXPECT_EQ(found, expected) << "view " << i;
    EXPECT_EQ(static_cast<int>(expected.size()), target.NumTags()) << "view " << i << ": the whole board in view";
    EXPECT_LT(std::sqrt(sum2 / (4.0 * detections.tags.size())), 0.05) << "view " << i;

    const BoardObservation observation = MatchToTarget(target, detections);
    EXPECT_EQ(observation.NumTags(), static_cast<int>(found.size()));
    const BoardPose pose = EstimateBoardPose(camera, observation, BoardPoseOptions{});
    ASSERT_TRUE(pose.has_pose) << pose.message;
    EXPECT_LT((pose.camera_from_target.position - poses[i].position).norm(), 0.5) << "mm, view " << i;
  }
}

TEST(TargetLayoutTest, IdMatrixBoardRendersAndDetectsInItsGeometry) {
  const Target target = Parse(kIdMatrix);
  ASSERT_EQ(target.NumTags(), 11);
  ExpectRenderedTagsDetectedInTheTargetsGeometry(target);
}

TEST(TargetLayoutTest, TagListBoardRendersAndDetectsInItsGeometry) {
  const Target target = Parse(kTagList);
  ASSERT_EQ(target.NumTags(), 8);
  ExpectRenderedTagsDetectedInTheTargetsGeometry(target);
}

TEST(TargetLayoutTest, TagListPrintsToScaleAndDetectsBack) {
  const Target target = Parse(kTagList);
  const double dpi = 150, px_per_mm = dpi / 25.4;
  const StatusOr<std::string> png = TargetPng(target, dpi);
  ASSERT_TRUE(png.ok()) << png.status().message();
  cv::Mat image = cv::imdecode(std::vector<uint8_t>(png->begin(), png->end()), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(image.empty());
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8);  // as a camera sees the print
  const Detections found = TagDetector::Create(ForTarget(DetectorOptions{}, target)).value()->Detect(image);
  ASSERT_EQ(static_cast<int>(found.tags.size()), target.NumTags());
  std::map<int, Eigen::Vector2d> bottom_left;  // page pixels, y down
  for (const TagDetection& tag : found.tags) bottom_left[tag.id] = tag.corners[0];
  ASSERT_EQ(bottom_left.count(17), 1u);
  for (int index = 0; index < target.NumTags(); ++index) {
    const int id = target.TagId(index);
    ASSERT_EQ(bottom_left.count(id), 1u) << id;
    const Eigen::Vector2d offset = target.TagOrigin(index) - target.TagOrigin(0);  // mm, y up
    EXPECT_NEAR(bottom_left[id].x() - bottom_left[17].x(), offset.x() * px_per_mm, 0.15) << id;
    EXPECT_NEAR(bottom_left[id].y() - bottom_left[17].y(), -offset.y() * px_per_mm, 0.15) << id;
  }
  // The leftmost black edge (tag 8, x = -45) sits 10 mm page margin + 9 mm sheet margin in.
  EXPECT_NEAR(bottom_left[8].x() + 0.5, 19 * px_per_mm, 0.15);
  EXPECT_THAT(TargetPrintCaption(target)[2], ::testing::HasSubstr("tag 17's bottom-left corner at x 0, y 0 mm"));
}

}  // namespace
}  // namespace hexcal

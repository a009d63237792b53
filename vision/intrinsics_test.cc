#include "vision/intrinsics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

using ::testing::HasSubstr;

// Views for calibration: 0.3-0.6 m, tilted up to 45°, spread over the image.
std::vector<cv::Mat> RenderViews(const Camera& camera, const Target& target, int count, uint64_t seed) {
  const Renderer renderer(camera, target, RenderOptions{});
  std::vector<cv::Mat> images;
  const std::vector<Pose> poses = RandomViewPoses(target, count, 300, 600, 45, 30, 0.25, seed);
  for (size_t i = 0; i < poses.size(); ++i) images.push_back(renderer.Render(poses[i], i).image);
  return images;
}

std::vector<std::string> Names(size_t count) {
  std::vector<std::string> names;
  for (size_t i = 0; i < count; ++i) names.push_back("view" + std::to_string(i));
  return names;
}

TEST(IntrinsicsTest, TwentyRenderedViewsLandWithinThreeSigmaOfTheTruth) {
  const Camera truth = SimulatedCamera();
  const Target target = DefaultTarget();
  const std::vector<cv::Mat> images = RenderViews(truth, target, 20, 8);
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, {});
  ASSERT_TRUE(result.ok()) << result.status().message();
  const Camera& c = result->camera;
  const std::array<double, 9> estimate = {
      c.fx, c.fy, c.cx, c.cy, c.distortion[0], c.distortion[1], c.distortion[2], c.distortion[3], c.distortion[4]};
  const std::array<double, 9> expected = {truth.fx,
                                          truth.fy,
                                          truth.cx,
                                          truth.cy,
                                          truth.distortion[0],
                                          truth.distortion[1],
                                          truth.distortion[2],
                                          truth.distortion[3],
                                          truth.distortion[4]};
  const char* names[9] = {"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3"};
  for (size_t i = 0; i < 9; ++i) {
    ASSERT_GT(result->std_dev[i], 0) << names[i];
    const double sigmas = (estimate[i] - expected[i]) / result->std_dev[i];
    std::cout << names[i] << " = " << estimate[i] << " (truth " << expected[i] << ", " << sigmas << " sigma)\n";
    EXPECT_LT(std::abs(sigmas), 3) << names[i];
  }
  EXPECT_EQ(result->used_views, 20);
  EXPECT_LT(result->rms_px, 0.1);
  EXPECT_EQ(c.width, 1024);
  const cv::Mat coverage = CoverageImage(*result);
  EXPECT_EQ(coverage.size(), cv::Size(1024, 768));
  EXPECT_GT(CoverageFraction(*result), 0.5);
  const CameraFileExtras extras = ExtrasOf(*result);
  EXPECT_EQ(extras.std_dev.size(), 9u);
  EXPECT_EQ(extras.per_view_rms_px.size(), 20u);
}

TEST(IntrinsicsTest, TooFewViewsIsAClearError) {
  const Target target = DefaultTarget();
  std::vector<cv::Mat> images = RenderViews(SimulatedCamera(), target, 3, 1);
  images.push_back(cv::Mat(768, 1024, CV_8U, cv::Scalar(90)));  // no target
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, {});
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.status().message(),
              HasSubstr("too few usable views: 3 of 4 images show at least 4 target tags; at least 8 are needed"));
}

TEST(IntrinsicsTest, ImagesOfDifferentSizesAreAnError) {
  const Target target = DefaultTarget();
  std::vector<cv::Mat> images = RenderViews(SimulatedCamera(), target, 2, 1);
  images.push_back(cv::Mat(480, 640, CV_8U, cv::Scalar(90)));
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, {});
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.status().message(),
              HasSubstr("images have different sizes: view0 is 1024 x 768, view2 is 640 x 480"));
}

}  // namespace
}  // namespace hexcal

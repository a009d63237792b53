#include "vision/renderer.h"

#include <gtest/gtest.h>

#include "tests/test_support.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

// Fronto-parallel, upright: camera x = target x, camera y = -target y.
Pose FrontoParallel(const Target& target, double distance) {
  Pose pose;
  pose.rotation = Eigen::Vector3d(1, -1, -1).asDiagonal();
  pose.position =
      Eigen::Vector3d(0, 0, distance) - pose.rotation * Eigen::Vector3d(target.Width() / 2, target.Height() / 2, 0);
  return pose;
}

Camera PinholeCamera() {
  Camera camera = SimulatedCamera();
  camera.distortion = {0, 0, 0, 0, 0};
  return camera;
}

RenderOptions Clean() {
  RenderOptions options;
  options.lighting_gradient = 0;
  options.vignetting = 0;
  options.blur_sigma_px = 0;
  options.noise_sigma = 0;
  options.shot_noise = 0;
  return options;
}

TEST(RendererTest, SameSeedSameImageOtherSeedOtherImage) {
  const Target target = DefaultTarget();
  const Pose pose = RandomViewPoses(target, 1, 450, 550, 30, 20, 0.1, 7)[0];
  RenderOptions options;
  options.seed = 5;
  const Renderer a(SimulatedCamera(), target, options);
  const Renderer b(SimulatedCamera(), target, options);
  const cv::Mat first = a.Render(pose, 3).image, again = b.Render(pose, 3).image;
  EXPECT_EQ(cv::norm(first, again, cv::NORM_L1), 0);
  options.seed = 6;
  const Renderer c(SimulatedCamera(), target, options);
  EXPECT_GT(cv::norm(first, c.Render(pose, 3).image, cv::NORM_L1), 0);
  EXPECT_GT(cv::norm(first, a.Render(pose, 4).image, cv::NORM_L1), 0);  // another image index
}

TEST(RendererTest, BlackAreaIsExactInACleanFrontoParallelView) {
  const Target target = DefaultTarget();
  const Camera camera = PinholeCamera();
  RenderOptions options = Clean();
  options.background_level = options.white_level;  // the sheet's edge does not count
  const double distance = 600;
  const Renderer renderer(camera, target, options);
  const RenderedView view = renderer.Render(FrontoParallel(target, distance), 0);
  // Σ black fraction over the image = black cells × cell area in pixels².
  double black_pixels = 0;
  for (int v = 0; v < view.image.rows; ++v) {
    for (int u = 0; u < view.image.cols; ++u) {
      const double value = view.image.at<uint8_t>(v, u);
      black_pixels += (options.white_level - value) / (options.white_level - options.black_level);
    }
  }
  int black_cells = 0;
  for (const TagCells& tag : TagCellsOf(target.family, target.first_id, target.NumTags())) {
    black_cells += static_cast<int>(std::count(tag.black.begin(), tag.black.end(), 1));
  }
  const double cell_px = camera.fx * target.tag_size / 8 / distance;
  // Rounding to 8 bits leaves at most half a grey level per edge pixel.
  EXPECT_NEAR(black_pixels / (black_cells * cell_px * cell_px), 1, 2e-3);
}

TEST(RendererTest, CornersAreProjectedWithTheCameraModel) {
  const Target target = DefaultTarget();
  const Camera camera = SimulatedCamera();
  const Renderer renderer(camera, target, RenderOptions{});
  const Pose pose = RandomViewPoses(target, 1, 400, 400, 20, 10, 0.05, 2)[0];
  const RenderedView view = renderer.Render(pose, 0);
  ASSERT_EQ(view.corners.size(), 4u * target.NumTags());
  int visible = 0;
  for (const ProjectedCorner& c : view.corners) {
    const Eigen::Vector3d p = pose * target.TagCorners(c.tag_id)[static_cast<size_t>(c.corner)];
    EXPECT_TRUE(testing::MatrixNear(c.pixel, camera.Project(p), 1e-9));
    visible += c.visible;
  }
  EXPECT_EQ(visible, 4 * target.NumTags());
}

TEST(RendererTest, PosesLookAtTheTarget) {
  const Target target = DefaultTarget();
  for (const Pose& pose : RandomViewPoses(target, 50, 300, 800, 40, 30, 0.2, 11)) {
    const Eigen::Vector3d centre = pose * Eigen::Vector3d(target.Width() / 2, target.Height() / 2, 0);
    EXPECT_GE(centre.z(), 300 - 1e-9);
    EXPECT_LE(centre.z(), 800 + 1e-9);
    EXPECT_LE(std::abs(centre.x()), 0.2 * centre.z() + 1e-9);
    // The printed face (target +z) looks at the camera, tilted by at most 40°.
    const Eigen::Vector3d normal = pose.rotation.col(2);
    EXPECT_LT(normal.z(), -std::cos(DegToRad(40)) + 1e-9);
    EXPECT_NEAR(pose.rotation.determinant(), 1, 1e-12);
  }
}

TEST(RendererTest, OccluderHidesCorners) {
  const Target target = DefaultTarget();
  RenderOptions options;
  options.occlusion_probability = 1;
  const Renderer renderer(SimulatedCamera(), target, options);
  int hidden = 0;
  for (uint64_t i = 0; i < 4; ++i) {
    const RenderedView view = renderer.Render(FrontoParallel(target, 500), i);
    for (const ProjectedCorner& c : view.corners) hidden += !c.visible;
  }
  EXPECT_GT(hidden, 0);
}

TEST(RendererTest, OptionsAreValidated) {
  RenderOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.black_level = 250;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_EQ(error, "black_level must be darker than white_level");
  options = RenderOptions{};
  options.occlusion_probability = 2;
  EXPECT_FALSE(options.IsValid(&error));
}

TEST(StableRandomTest, IsReproducibleAndNormal) {
  StableRandom a(42), b(42);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.Next(), b.Next());
  StableRandom r(1);
  double sum = 0, sum2 = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = r.Normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0, 0.03);
  EXPECT_NEAR(sum2 / n, 1, 0.03);
}

}  // namespace
}  // namespace hexcal

#include "vision/intrinsics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "tests/test_support.h"
#include "vision/intrinsics_diagnosis.h"
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
  EXPECT_EQ(c.model, CameraModel::kRadTan);
  const std::vector<double> estimate = c.ParameterValues(), expected = truth.ParameterValues();
  const std::vector<std::string> names = c.ParameterNames();
  ASSERT_EQ(result->std_dev.size(), 9u);
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
  // Every corner of every used view has its residual, and they make up the RMS.
  size_t corners = 0;
  double sum = 0;
  for (const CalibrationView& view : result->views) corners += view.used ? view.corners.size() : 0;
  ASSERT_EQ(result->corner_residuals.size(), corners);
  for (const CornerResidual& corner : result->corner_residuals) {
    const CalibrationView& view = result->views[corner.image];
    ASSERT_TRUE(view.used);
    EXPECT_NE(std::find(view.corners.begin(), view.corners.end(), corner.observed), view.corners.end());
    sum += corner.residual.squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(sum / corners), result->rms_px, 1e-9);
  const CameraFileExtras extras = ExtrasOf(*result);
  EXPECT_EQ(extras.std_dev.size(), 9u);
  EXPECT_EQ(extras.per_view_rms_px.size(), 20u);
  // Two halves of 10 views agree within their σ, and project the image alike
  // to a fraction of a pixel (the model and the data are consistent).
  const CrossValidation& cross = result->cross_validation;
  std::cout << DescribeCrossValidation(cross) << "\n";
  ASSERT_TRUE(cross.done);
  EXPECT_EQ(cross.views_a + cross.views_b, 20);
  ASSERT_EQ(cross.z.size(), 4u);
  EXPECT_LT(cross.max_z, 3);
  // In pixels the halves differ most where neither saw corners (the image's
  // corners, extrapolated by each half's distortion): 0.36 px RMS here.
  EXPECT_LT(cross.rms_px, 1);
}

// The comparison itself against known cameras: identical halves differ by
// nothing, and a principal point 3 px off shows as 3 px everywhere and as
// 3 / √(σa² + σb²) σ.
TEST(IntrinsicsTest, CompareHalvesSeesADifferentCamera) {
  const Camera truth = SimulatedCamera();
  Camera shifted = truth;
  shifted.cx += 3;
  const std::vector<double> sigma = {0.5, 0.5, 0.4, 0.4};
  const CrossValidation same = CompareHalves(truth, truth, sigma, truth, sigma);
  EXPECT_EQ(same.rms_px, 0);
  EXPECT_EQ(same.max_z, 0);
  const CrossValidation apart = CompareHalves(truth, truth, sigma, shifted, sigma);
  EXPECT_NEAR(apart.rms_px, 3, 1e-9);
  EXPECT_NEAR(apart.max_z, 3 / std::hypot(0.4, 0.4), 1e-9);
}

// The judgement against its stated thresholds: good within 0.5 px RMS and 3 σ;
// poor beyond either, with what to do; without σ (fisheye) on pixels alone.
TEST(IntrinsicsTest, CrossValidationIsJudgedAgainstItsThresholds) {
  const Camera truth = SimulatedCamera();
  Camera shifted = truth;
  const std::vector<double> sigma = {0.5, 0.5, 0.4, 0.4};
  shifted.cx += 0.4;  // 0.4 px everywhere, 0.71 σ
  CrossValidation near = CompareHalves(truth, truth, sigma, shifted, sigma);
  near.views_a = near.views_b = 8;
  EXPECT_TRUE(CrossValidationGood(near));
  EXPECT_THAT(DescribeCrossValidation(near), ::testing::EndsWith(": good (within 0.5 px RMS and 3 sigma)"));
  shifted.cx = truth.cx + 1;  // 1 px everywhere, 1.8 σ
  const CrossValidation far = CompareHalves(truth, truth, sigma, shifted, sigma);
  EXPECT_FALSE(CrossValidationGood(far));
  EXPECT_THAT(DescribeCrossValidation(far), ::testing::HasSubstr(": poor (good is within 0.5 px RMS and 3 sigma); "
                                                                 "the views do not determine the camera"));
  const std::vector<double> tight = {0.05, 0.05, 0.04, 0.04};
  shifted.cx = truth.cx + 0.4;  // 0.4 px, but 7 σ of these σ
  const CrossValidation overconfident = CompareHalves(truth, truth, tight, shifted, tight);
  EXPECT_FALSE(CrossValidationGood(overconfident));
  EXPECT_THAT(DescribeCrossValidation(overconfident), ::testing::HasSubstr("the sigma are too small for the data"));
  const CrossValidation fisheye = CompareHalves(truth, truth, {}, shifted, {});
  EXPECT_TRUE(CrossValidationGood(fisheye));
  EXPECT_THAT(DescribeCrossValidation(fisheye), ::testing::EndsWith(": good (within 0.5 px RMS)"));
  EXPECT_FALSE(CrossValidationGood(CrossValidation{}));  // not done: no judgement of good
}

// A view far noisier than the rest (a dim, high-gain frame: its corners
// scatter ten times more, without bias) is under the 0.5 px floor of an
// outlier: left out as over ten times the median, kept with keep_outliers and
// then named.
TEST(IntrinsicsTest, AViewTenTimesWorseThanTheMedianIsLeftOutUnlessKept) {
  const Camera truth = SimulatedCamera();
  const Target target = DefaultTarget();
  std::vector<cv::Mat> images = RenderViews(truth, target, 12, 8);
  cv::Mat noise(images[3].size(), CV_16S);
  cv::randn(noise, 0, 40);
  cv::Mat noisy;
  images[3].convertTo(noisy, CV_16S);
  noisy += noise;
  noisy.convertTo(images[3], CV_8U);
  IntrinsicsOptions options;
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_FALSE(result->views[3].used);
  EXPECT_THAT(result->views[3].reason, ::testing::StartsWith("outlier: RMS "));
  EXPECT_EQ(result->used_views, 11);
  options.keep_outliers = true;
  StatusOr<IntrinsicsResult> kept = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, options);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_EQ(kept->used_views, 12);
  const double rms = kept->views[3].rms_px;
  std::cout << DescribeWorstView(*kept, options.outlier_factor) << "\n";
  EXPECT_LT(rms, options.outlier_min_rms_px);  // the floor alone would have kept it
  EXPECT_THAT(DescribeWorstView(*kept, options.outlier_factor), ::testing::StartsWith("view3 fits "));
}

// A used view far worse than the median is named; none when the views agree.
TEST(IntrinsicsTest, AViewFarWorseThanTheMedianIsNamed) {
  IntrinsicsResult result;
  for (int i = 0; i < 8; ++i) result.views.push_back({"view_" + std::to_string(i) + ".png", 36, true, "", 0.05});
  EXPECT_EQ(DescribeWorstView(result, 3), "");
  result.views[5].rms_px = 0.7;
  EXPECT_THAT(DescribeWorstView(result, 3),
              ::testing::StartsWith("view_5.png fits 14x worse than the median view (RMS 0.7 px, median 0.05 px)"));
  result.views[5].used = false;  // left out already: not named again
  EXPECT_EQ(DescribeWorstView(result, 3), "");
}

// A 1024 x 768 fisheye (70° off axis in the image corners), calibrated with
// cv::fisheye from rendered views (docs/vision.md#camera-models).
TEST(IntrinsicsTest, FisheyeFromRenderedViewsRecoversTheFocalLengthsAndCentre) {
  const Camera truth = SimulatedFisheyeCamera();
  const Target target = DefaultTarget();
  const Renderer renderer(truth, target, RenderOptions{});
  std::vector<cv::Mat> images;
  const std::vector<Pose> poses = RandomViewPoses(target, 16, 220, 400, 40, 30, 0.6, 11);
  for (size_t i = 0; i < poses.size(); ++i) images.push_back(renderer.Render(poses[i], i).image);
  IntrinsicsOptions options;
  options.model = CameraModel::kPinholeEqui;
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const Camera& c = result->camera;
  std::cout << "pinhole-equi: fx " << c.fx << " fy " << c.fy << " cx " << c.cx << " cy " << c.cy << " k "
            << c.distortion[0] << " " << c.distortion[1] << " " << c.distortion[2] << " " << c.distortion[3] << ", RMS "
            << result->rms_px << " px, " << result->used_views << " views\n";
  EXPECT_EQ(c.model, CameraModel::kPinholeEqui);
  EXPECT_NEAR(c.fx / truth.fx, 1, 0.005);
  EXPECT_NEAR(c.fy / truth.fy, 1, 0.005);
  EXPECT_NEAR(c.cx, truth.cx, 2);
  EXPECT_NEAR(c.cy, truth.cy, 2);
  EXPECT_LT(result->rms_px, 0.15);
  EXPECT_GE(result->used_views, 14);
  EXPECT_TRUE(result->std_dev.empty());  // cv::fisheye::calibrate gives none
  const CameraFileExtras extras = ExtrasOf(*result);
  EXPECT_TRUE(extras.std_dev.empty());
  EXPECT_EQ(extras.per_view_rms_px.size(), static_cast<size_t>(result->used_views));
}

TEST(IntrinsicsTest, RationalModelGivesTheStandardDeviationsOfItsTwelveParameters) {
  Camera truth = SimulatedCamera();
  truth.model = CameraModel::kRational;
  truth.distortion = {0.4, -0.1, 0.0004, -0.0003, 0.02, 0.68, 0.02, 0.01};
  const Target target = DefaultTarget();
  const std::vector<cv::Mat> images = RenderViews(truth, target, 16, 8);
  IntrinsicsOptions options;
  options.model = CameraModel::kRational;
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, Names(images.size()), target, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->camera.model, CameraModel::kRational);
  // fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6, from views of a lens that needs the
  // denominator (of a plain radtan lens, some come out NaN: not determined).
  ASSERT_EQ(result->std_dev.size(), 12u);
  std::cout << "rational: fx " << result->camera.fx << " +- " << result->std_dev[0] << ", cx " << result->camera.cx
            << ", cy " << result->camera.cy << ", RMS " << result->rms_px << " px\n";
  for (size_t i = 0; i < 4; ++i) EXPECT_GT(result->std_dev[i], 0) << i;
  EXPECT_LT(result->rms_px, 0.15);
  EXPECT_NEAR(result->camera.fx / truth.fx, 1, 0.005);
  EXPECT_NEAR(result->camera.cx, truth.cx, 2);
  EXPECT_NEAR(result->camera.cy, truth.cy, 2);
  const std::string file = CameraToOpenCvYaml(result->camera, ExtrasOf(*result));
  StatusOr<Camera> back = ParseCameraFile(file, "rational.yaml");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->distortion, result->camera.distortion);
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

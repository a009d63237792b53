// Detection on photographs no hexcal code made (tests/data/real/README.md):
// the tag counts the peers' own test suites expect, and corners that a
// published calibration confirms.
#include <gtest/gtest.h>

#include <iostream>
#include <set>

#include "tests/test_support.h"
#include "vision/board_pose.h"
#include "vision/detection.h"
#include "vision/fisheye_init.h"
#include "vision/intrinsics.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;

std::string RealImage(const std::string& name) { return (SourceDir() / "tests/data/real" / name).string(); }

Target KalibrGrid() {
  return LoadTarget((SourceDir() / "resources/targets/kalibr-aprilgrid-6x6-88mm.yaml").string()).value();
}

// The board pose through `camera` from the edge-fitted corners, and from the
// quad corners the edge fit starts from (refine_edges off), both detected in
// the undistorted image.
struct EdgeFitAndQuadPoses {
  BoardObservation fitted;
  BoardPose with_fit, without;
};

EdgeFitAndQuadPoses PosesWithAndWithoutEdgeFit(const Camera& camera, const Target& grid, const cv::Mat& gray) {
  auto ideal = std::make_shared<const IdealPixelMap>(camera);
  DetectorOptions options = ForTarget(DetectorOptions{}, grid);
  EdgeFitAndQuadPoses poses;
  poses.fitted = MatchToTarget(grid, TagDetector::Create(options, ideal).value()->Detect(gray));
  options.refine_edges = false;
  const BoardObservation quads = MatchToTarget(grid, TagDetector::Create(options, ideal).value()->Detect(gray));
  poses.with_fit = EstimateBoardPose(camera, poses.fitted, BoardPoseOptions{});
  poses.without = EstimateBoardPose(camera, quads, BoardPoseOptions{});
  return poses;
}

struct PeerCount {
  const char* file;
  int border_bits;
  size_t tags;  // powei-lin/aprilgrid-rs tests/test_detector.rs, powei-lin/aprilgrid tests/test_detection.py
};

class PeerCountTest : public ::testing::TestWithParam<PeerCount> {};

TEST_P(PeerCountTest, FindsEveryTagThePeersFind) {
  const PeerCount& expected = GetParam();
  ImageNotes notes;
  const cv::Mat gray = LoadGrayImage(RealImage(expected.file), &notes).value();
  DetectorOptions options;
  options.border_bits = expected.border_bits;
  const Detections found = TagDetector::Create(options).value()->Detect(gray);
  std::set<int> ids;
  int refined = 0;
  for (const TagDetection& tag : found.tags) {
    ids.insert(tag.id);
    refined += tag.refined ? 1 : 0;
  }
  std::cout << expected.file << ": " << found.tags.size() << " tags (" << refined << " edge-fitted), "
            << found.rejected.size() << " rejected; " << DescribeImageNotes(notes) << "\n";
  EXPECT_EQ(found.tags.size(), expected.tags);
  EXPECT_EQ(ids.size(), found.tags.size()) << "an id found twice";
}

INSTANTIATE_TEST_SUITE_P(RealPhotos, PeerCountTest,
                         ::testing::Values(PeerCount{"EuRoC.png", 2, 36}, PeerCount{"TUM_VI.png", 2, 36},
                                           PeerCount{"r45.png", 2, 36}, PeerCount{"iphone.png", 2, 66},
                                           PeerCount{"t36h11_2bit_margin.jpg", 2, 36},
                                           PeerCount{"t36h11_1bit_margin.png", 1, 154},
                                           PeerCount{"tumvi-right.png", 2, 36}, PeerCount{"tumvi-top.png", 2, 35}));

TEST(RealImageFilesTest, DeepColourAndAlphaImagesAreRead) {
  ImageNotes notes;
  const cv::Mat tum = LoadGrayImage(RealImage("TUM_VI.png"), &notes).value();
  EXPECT_EQ(notes.bits, 16);
  EXPECT_LT(notes.range_low, notes.range_high);
  double low = 0, high = 0;
  cv::minMaxLoc(tum, &low, &high);
  EXPECT_EQ(low, 0);  // the range is stretched, not clipped to the high byte
  EXPECT_EQ(high, 255);
  LoadGrayImage(RealImage("iphone.png"), &notes).value();
  EXPECT_EQ(notes.channels, 3);
  LoadGrayImage(RealImage("t36h11_1bit_margin.png"), &notes).value();
  EXPECT_EQ(notes.channels, 4);
}

// EuRoC cam0 has a published calibration (pinhole-radtan, tests/data/real/README.md):
// the board pose from the detected corners must fit it to a fraction of a
// pixel, which only corners in the right order and place can do. The edge
// fit must do at least as well as the quad corners it starts from.
TEST(RealImagePoseTest, EuRoCCornersFitThePublishedCalibration) {
  Camera euroc;
  euroc.width = 752;
  euroc.height = 480;
  euroc.fx = 458.654;
  euroc.fy = 457.296;
  euroc.cx = 367.215;
  euroc.cy = 248.375;
  euroc.distortion = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0};
  const EdgeFitAndQuadPoses poses =
      PosesWithAndWithoutEdgeFit(euroc, KalibrGrid(), LoadGrayImage(RealImage("EuRoC.png")).value());
  std::cout << "EuRoC board pose RMS: edge fit " << poses.with_fit.rms_px << " px (" << poses.fitted.NumTags()
            << " tags), quad corners " << poses.without.rms_px << " px, distance "
            << poses.with_fit.camera_from_target.position.norm() << " m\n";
  ASSERT_TRUE(poses.with_fit.has_pose);
  EXPECT_EQ(poses.fitted.NumTags(), 36);
  EXPECT_LT(poses.with_fit.rms_px, 0.5);
  // The quad corners are snapped to the edges as the library does
  // (vision/quad_snap.h): on this lens the edge fit starts from corners
  // within 0.02 px RMS of its own result.
  EXPECT_LE(poses.with_fit.rms_px, poses.without.rms_px + 0.03);
}

// The TUM VI camera's published calibration (Kalibr pinhole-equi at 512 × 512,
// tests/data/real/README.md), at the frames' 1024 × 1024: f doubles, c → 2c + ½.
Camera PublishedTumVi() {
  Camera tum;
  tum.width = tum.height = 1024;
  tum.model = CameraModel::kPinholeEqui;
  tum.fx = 2 * 190.97847715128717;
  tum.fy = 2 * 190.9733070521226;
  tum.cx = 2 * 254.93170605935475 + 0.5;
  tum.cy = 2 * 256.8974428996504 + 0.5;
  tum.distortion = {0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202, 0.00020293673591811182};
  return tum;
}

// The published fisheye explains both real frames to a fraction of a pixel:
// the equidistant model, the 16-bit reading and the corners agree with Kalibr's.
TEST(RealImagePoseTest, TumViCornersFitThePublishedFisheye) {
  for (const char* file : {"TUM_VI.png", "r45.png"}) {
    const EdgeFitAndQuadPoses poses =
        PosesWithAndWithoutEdgeFit(PublishedTumVi(), KalibrGrid(), LoadGrayImage(RealImage(file)).value());
    std::cout << file << " board pose RMS with the published fisheye: edge fit " << poses.with_fit.rms_px
              << " px, quad corners " << poses.without.rms_px << " px\n";
    ASSERT_TRUE(poses.with_fit.has_pose) << file;
    EXPECT_LT(poses.with_fit.rms_px, 0.5) << file;
    EXPECT_LE(poses.with_fit.rms_px, poses.without.rms_px) << file;
  }
}

// Intrinsics from the two real frames alone, with the fisheye model, against
// the published calibration. Two views of one planar board pin the focal
// length and the principal point only loosely, so the frames are joined by
// renders through the published camera at other poses (tests/data/real/README.md:
// "plus renders if needed"); the real frames then still carry their own
// corners into the fit, and a wrong model, border or reading of them would
// pull it away.
TEST(RealImageIntrinsicsTest, TumViFisheyeAgreesWithThePublishedCalibration) {
  const Camera tum = PublishedTumVi();
  const Target grid = KalibrGrid();
  std::vector<cv::Mat> images = {LoadGrayImage(RealImage("TUM_VI.png")).value(),
                                 LoadGrayImage(RealImage("r45.png")).value()};
  std::vector<std::string> names = {"TUM_VI.png", "r45.png"};
  const std::vector<Pose> poses = RandomViewPoses(grid, 10, 0.45, 0.75, 35, 30, 0.12, 7);
  RenderOptions render;
  render.blur_sigma_px = 1.2;
  const Renderer renderer(tum, grid, render);
  for (size_t i = 0; i < poses.size(); ++i) {
    images.push_back(renderer.Render(poses[i], i).image);
    names.push_back("render_" + std::to_string(i));
  }
  IntrinsicsOptions options;
  options.model = CameraModel::kPinholeEqui;
  const IntrinsicsResult result = CalibrateIntrinsicsFromImages(images, names, grid, options).value();
  std::cout << "TUM VI fisheye from 2 real frames + " << poses.size() << " renders: fx " << result.camera.fx << " ("
            << tum.fx << "), fy " << result.camera.fy << " (" << tum.fy << "), cx " << result.camera.cx << " ("
            << tum.cx << "), cy " << result.camera.cy << " (" << tum.cy << "), RMS " << result.rms_px << " px\n";
  for (const CalibrationView& view : result.views) {
    if (view.file.rfind("render_", 0) != 0) {
      std::cout << "  " << view.file << ": " << (view.used ? "used" : view.reason) << ", RMS " << view.rms_px << " px\n";
      EXPECT_TRUE(view.used) << view.file;
    }
  }
  // The same calibration from the quad corners: the real frames fit it worse.
  options.detector.refine_edges = false;
  const IntrinsicsResult quads = CalibrateIntrinsicsFromImages(images, names, grid, options).value();
  for (size_t i = 0; i < 2; ++i) {
    std::cout << "  " << names[i] << ": RMS " << result.views[i].rms_px << " px from edge-fitted corners, "
              << quads.views[i].rms_px << " px from quad corners\n";
    EXPECT_LE(result.views[i].rms_px, quads.views[i].rms_px) << names[i];
  }
  EXPECT_NEAR(result.camera.fx / tum.fx, 1, 0.005);
  EXPECT_NEAR(result.camera.fy / tum.fy, 1, 0.005);
  EXPECT_NEAR(result.camera.cx, tum.cx, 2);
  EXPECT_NEAR(result.camera.cy, tum.cy, 2);
}

// The four real TUM VI frames alone (tests/data/real/README.md), no rendered
// view and no initial guess: the focal length the views agree on
// (vision/fisheye_init.h) starts the fisheye calibration, which must land on
// the published camera, within 0.5 % in f and 1 px in the principal point.
TEST(RealImageIntrinsicsTest, TumViFisheyeFromTheFourRealFramesAlone) {
  const Camera tum = PublishedTumVi();
  const Target grid = KalibrGrid();
  std::vector<cv::Mat> images;
  std::vector<std::string> names = {"TUM_VI.png", "r45.png", "tumvi-right.png", "tumvi-top.png"};
  for (const std::string& name : names) images.push_back(LoadGrayImage(RealImage(name)).value());
  IntrinsicsOptions options;
  options.model = CameraModel::kPinholeEqui;
  options.min_views = 4;
  const IntrinsicsResult result = CalibrateIntrinsicsFromImages(images, names, grid, options).value();
  std::cout << "TUM VI fisheye from the 4 real frames alone: fx " << result.camera.fx << " (" << tum.fx << "), fy "
            << result.camera.fy << " (" << tum.fy << "), cx " << result.camera.cx << " (" << tum.cx << "), cy "
            << result.camera.cy << " (" << tum.cy << "), k " << result.camera.distortion[0] << " "
            << result.camera.distortion[1] << " " << result.camera.distortion[2] << " " << result.camera.distortion[3]
            << ", RMS " << result.rms_px << " px, " << result.used_views << " views used\n";
  EXPECT_EQ(result.used_views, 4);
  EXPECT_NEAR(result.camera.fx / tum.fx, 1, 0.005);
  EXPECT_NEAR(result.camera.fy / tum.fy, 1, 0.005);
  EXPECT_NEAR(result.camera.cx, tum.cx, 1);
  EXPECT_NEAR(result.camera.cy, tum.cy, 1);
  EXPECT_LT(result.rms_px, 0.5);
}

// The start alone, from the quad corners of the four frames: near enough the
// published focal length for the calibration to converge (OpenCV's own start,
// side / π = 326 px, is 15 % short and does not).
TEST(RealImageIntrinsicsTest, FisheyeStartFindsTheFocalLengthOfTheRealFrames) {
  const Camera tum = PublishedTumVi();
  const Target grid = KalibrGrid();
  DetectorOptions options = ForTarget(DetectorOptions{}, grid);
  options.refine_edges = false;
  std::vector<BoardObservation> observations;
  for (const char* name : {"TUM_VI.png", "r45.png", "tumvi-right.png", "tumvi-top.png"}) {
    observations.push_back(
        MatchToTarget(grid, TagDetector::Create(options).value()->Detect(LoadGrayImage(RealImage(name)).value())));
  }
  std::vector<const BoardObservation*> views;
  for (const BoardObservation& observation : observations) views.push_back(&observation);
  const std::optional<FisheyeStart> start = EquidistantStart(views, cv::Size(1024, 1024));
  ASSERT_TRUE(start);
  std::cout << "fisheye start: f " << start->f << " px (published " << tum.fx << "), median view RMS "
            << start->median_rms_px << " px\n";
  EXPECT_NEAR(start->f / tum.fx, 1, 0.05);
  EXPECT_LT(start->median_rms_px, 10);
}

}  // namespace
}  // namespace hexcal

// The AprilTag library as the floor under hexcal's detection: on every image
// in tests/data, and on each real photograph made harder (smaller, JPEG,
// blurred, tilted), hexcal finds every tag that the library's own detector
// finds with its default settings. The reference is called here through the
// library's C API as its demo does, not through hexcal's wrapper
// (vision/library_detector.h), so a fault in the wrapper cannot hide a miss.
#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/csv.h"
#include "tests/test_support.h"
#include "vision/detection.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;

struct LibraryTag {
  int id = 0;
  int hamming = 0;
  std::array<Eigen::Vector2d, 4> corners;  // OpenCV pixel convention
};

// apriltag_demo's set-up: apriltag_detector_create's defaults and the
// family added with its default two corrected bits; `quad_decimate` 1 is the
// library's full-resolution (most accurate) quad fit.
std::vector<LibraryTag> DetectWithLibrary(const cv::Mat& gray, float quad_decimate = 2) {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  apriltag_detector_add_family(detector, family);
  detector->quad_decimate = quad_decimate;
  image_u8_t image{gray.cols, gray.rows, static_cast<int32_t>(gray.step[0]), const_cast<uint8_t*>(gray.data)};
  zarray_t* found = apriltag_detector_detect(detector, &image);
  std::vector<LibraryTag> tags;
  for (int i = 0; i < zarray_size(found); ++i) {
    apriltag_detection_t* detection = nullptr;
    zarray_get(found, i, &detection);
    LibraryTag tag{detection->id, detection->hamming, {}};
    for (size_t k = 0; k < 4; ++k) tag.corners[k] = {detection->p[k][0] - 0.5, detection->p[k][1] - 0.5};
    tags.push_back(tag);
  }
  apriltag_detections_destroy(found);
  apriltag_detector_remove_family(detector, family);
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
  return tags;
}

Eigen::Vector2d Centre(const std::array<Eigen::Vector2d, 4>& corners) {
  return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
}

// The hexcal tag that is the library's `tag` (same id, same place), or null.
const TagDetection* Matching(const LibraryTag& tag, const Detections& found) {
  const double side = (tag.corners[1] - tag.corners[0]).norm();
  for (const TagDetection& mine : found.tags) {
    if (mine.id == tag.id && (Centre(mine.corners) - Centre(tag.corners)).norm() < 0.25 * side) return &mine;
  }
  return nullptr;
}

double LargestCornerGap(const std::array<Eigen::Vector2d, 4>& a, const std::array<Eigen::Vector2d, 4>& b) {
  double gap = 0;
  for (size_t k = 0; k < 4; ++k) gap = std::max(gap, (a[k] - b[k]).norm());
  return gap;
}

// Kalibr's aprilgrids print two border cells; everything else in tests/data
// is the library's one-cell layout (tests/data/real/README.md).
int BorderBitsOf(const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  for (const char* two : {"EuRoC", "TUM_VI", "r45", "iphone", "2bit", "tumvi-"}) {
    if (name.find(two) != std::string::npos) return 2;
  }
  return 1;
}

struct Variant {
  std::string name;
  cv::Mat image;
};

cv::Mat ThroughJpeg(const cv::Mat& gray, int quality) {
  std::vector<uint8_t> bytes;
  cv::imencode(".jpg", gray, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  return cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
}

// The board seen 35° off its normal about the vertical axis, by a homography.
cv::Mat Tilted(const cv::Mat& gray) {
  const float w = static_cast<float>(gray.cols), h = static_cast<float>(gray.rows);
  const std::vector<cv::Point2f> from{{0, 0}, {w, 0}, {w, h}, {0, h}};
  const std::vector<cv::Point2f> to{{0.05f * w, 0.12f * h}, {0.9f * w, 0}, {0.9f * w, h}, {0.05f * w, 0.88f * h}};
  cv::Mat out;
  cv::warpPerspective(gray, out, cv::getPerspectiveTransform(from, to), gray.size(), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT, cv::Scalar(128));
  return out;
}

// Small tags with thin borders in JPEG noise and blur: what the library's own
// test photos hold. Each size is the image's longest side in pixels.
std::vector<Variant> Variants(const cv::Mat& gray) {
  std::vector<Variant> variants{{"as is", gray}};
  const int longest = std::max(gray.cols, gray.rows);
  for (int target : {1600, 800, 480, 320, 200}) {
    if (target >= longest) continue;
    const double factor = static_cast<double>(target) / longest;
    const std::string size = std::to_string(target) + " px";
    cv::Mat scaled, blurred;
    cv::resize(gray, scaled, cv::Size(), factor, factor, cv::INTER_AREA);
    cv::GaussianBlur(scaled, blurred, cv::Size(), 1.0);
    variants.push_back({size, scaled});
    variants.push_back({size + ", JPEG 60", ThroughJpeg(scaled, 60)});
    variants.push_back({size + ", blur 1 px", blurred});
    variants.push_back({size + ", tilted, JPEG 75", ThroughJpeg(Tilted(scaled), 75)});
  }
  return variants;
}

std::vector<std::filesystem::path> ImagesInTestData() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(SourceDir() / "tests/data")) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && (extension == ".png" || extension == ".jpg")) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct FloorCount {
  size_t library = 0, found = 0, library_found_by_hexcal = 0, also_rejected = 0, cut_by_border = 0;
};

bool CutByTheBorder(const LibraryTag& tag, const Detections& found) {
  return std::any_of(found.rejected.begin(), found.rejected.end(), [&](const RejectedTag& rejected) {
    return rejected.id == tag.id && rejected.reason == "a corner is outside the image";
  });
}

// hexcal as configured with the library's acceptance (two corrected bits, any
// margin); and hexcal with its defaults, which must at least report every
// library tag it rejects.
FloorCount CompareOnImage(const cv::Mat& gray, int border_bits, const std::string& label) {
  DetectorOptions like_library;
  like_library.border_bits = border_bits;
  like_library.max_hamming = 2;
  like_library.min_decision_margin = 0;
  DetectorOptions defaults;
  defaults.border_bits = border_bits;
  const Detections mine = TagDetector::Create(like_library).value()->Detect(gray);
  const Detections mine_default = TagDetector::Create(defaults).value()->Detect(gray);
  FloorCount count;
  const std::vector<LibraryTag> library = DetectWithLibrary(gray);
  count.library = library.size();
  count.found = mine.tags.size();
  for (const LibraryTag& tag : library) {
    const TagDetection* match = Matching(tag, mine);
    // hexcal refuses, and reports, a tag cut by the image's border (the
    // library extrapolates its corners); it is not a tag missed.
    if (!match && CutByTheBorder(tag, mine)) {
      ++count.cut_by_border;
      continue;
    }
    EXPECT_TRUE(match) << label << ": the library finds tag " << tag.id << " at (" << Centre(tag.corners).transpose()
                       << "), hexcal does not";
    if (!match) continue;
    ++count.library_found_by_hexcal;
    const bool reported = Matching(tag, mine_default) ||
                          std::any_of(mine_default.rejected.begin(), mine_default.rejected.end(),
                                      [&](const RejectedTag& rejected) { return rejected.id == tag.id; });
    EXPECT_TRUE(reported) << label << ": tag " << tag.id << " neither accepted nor reported rejected by default";
    count.also_rejected += Matching(tag, mine_default) ? 0 : 1;
  }
  return count;
}

TEST(LibraryFloorTest, EveryTagTheLibraryFindsInTestData) {
  const std::vector<std::filesystem::path> files = ImagesInTestData();
  ASSERT_GE(files.size(), 9u);
  size_t library_total = 0, hexcal_total = 0;
  for (const std::filesystem::path& file : files) {
    StatusOr<cv::Mat> loaded = LoadGrayImage(file.string());
    if (!loaded.ok()) continue;  // the bad-input corpus: files that must not load
    const int border_bits = BorderBitsOf(file);
    for (const Variant& variant : Variants(*loaded)) {
      const std::string label = file.filename().string() + " (" + variant.name + ")";
      const FloorCount count = CompareOnImage(variant.image, border_bits, label);
      library_total += count.library;
      hexcal_total += count.found;
      if (count.library == 0 && count.found == 0) continue;
      std::cout << std::left << std::setw(46) << label << " library " << std::setw(4) << count.library << " hexcal "
                << std::setw(4) << count.found << " (" << count.library_found_by_hexcal << " of the library's, "
                << count.also_rejected << " of them rejected by default; " << count.cut_by_border
                << " cut by the border, refused)\n";
    }
  }
  std::cout << "all images: library " << library_total << " tags, hexcal " << hexcal_total << "\n";
  EXPECT_GE(hexcal_total, library_total);
}

// Corners before the edge fit against the library's at full resolution
// (quad_decimate 1, its most accurate quad fit), on boards whose tags stand
// apart in white (on an aprilgrid the library's quad runs into the corner
// squares: 13 px off on the print chart at 1600 px). Rendered at 1 to 3.5 m
// so that tags shrink to about 12 px, some through JPEG. Both are also held to
// the renderer's true corners.
TEST(LibraryFloorTest, QuadCornersAgreeWithTheLibrarysAtFullResolution) {
  const Target target = LoadTarget((SourceDir() / "resources/targets/aprilgrid-6x6.yaml").string()).value();
  const Camera camera = SimulatedCamera();
  const Renderer renderer(camera, target, RenderOptions{});
  const std::vector<Pose> poses = RandomViewPoses(target, 12, 1000, 3500, 40, 180, 0.15, 5);
  DetectorOptions options;
  options.refine_edges = false;
  options.max_hamming = 2;
  options.min_decision_margin = 0;
  std::unique_ptr<TagDetector> detector = TagDetector::Create(options).value();
  double worst_gap = 0, worst_library_error = 0, worst_hexcal_error = 0;
  int compared = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const RenderedView view = renderer.Render(poses[i], i);
    const cv::Mat gray = i % 2 ? ThroughJpeg(view.image, 80) : view.image;
    const Detections mine = detector->Detect(gray);
    for (const LibraryTag& tag : DetectWithLibrary(gray, 1)) {
      const TagDetection* match = Matching(tag, mine);
      ASSERT_TRUE(match) << "view " << i << ": the library finds tag " << tag.id << ", hexcal does not";
      std::array<Eigen::Vector2d, 4> truth;
      for (const ProjectedCorner& corner : view.corners) {
        if (corner.tag_id == tag.id) truth[static_cast<size_t>(corner.corner)] = corner.pixel;
      }
      const double gap = LargestCornerGap(tag.corners, match->corners);
      EXPECT_LE(gap, 0.5) << "view " << i << ": tag " << tag.id;
      worst_gap = std::max(worst_gap, gap);
      worst_library_error = std::max(worst_library_error, LargestCornerGap(tag.corners, truth));
      worst_hexcal_error = std::max(worst_hexcal_error, LargestCornerGap(match->corners, truth));
      ++compared;
    }
  }
  std::cout << compared << " tags: hexcal's quad corners within " << worst_gap
            << " px of the library's; from the truth: library " << worst_library_error << " px, hexcal "
            << worst_hexcal_error << " px\n";
  EXPECT_GE(compared, 100);
}

}  // namespace
}  // namespace hexcal

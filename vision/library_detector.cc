#include "vision/library_detector.h"

#include <apriltag/apriltag.h>

#include "vision/tag_family.h"

namespace hexcal {
namespace {

// AprilTag measures pixels from the top-left corner of the top-left pixel;
// OpenCV from that pixel's centre (docs/conventions.md).
constexpr double kAprilTagToOpenCv = -0.5;

struct DetectionsDeleter {
  void operator()(zarray_t* detections) const { apriltag_detections_destroy(detections); }
};
using DetectionsPtr = std::unique_ptr<zarray_t, DetectionsDeleter>;

}  // namespace

struct LibraryDetector::Impl {
  AprilTagFamilyPtr family;
  apriltag_detector_t* detector = nullptr;

  ~Impl() {
    if (detector) {
      apriltag_detector_remove_family(detector, family.get());
      apriltag_detector_destroy(detector);
    }
  }
};

StatusOr<std::unique_ptr<LibraryDetector>> LibraryDetector::Create(const std::string& family,
                                                                   const LibraryDetectorSettings& settings) {
  if (!FindTagFamily(family)) return Status::BadInput("library detector: family '" + family + "' is not supported");
  if (settings.threads < 1 || settings.threads > 64)
    return Status::BadInput("library detector: threads must be in 1..64");
  if (!(settings.quad_decimate >= 1 && settings.quad_decimate <= 8))
    return Status::BadInput("library detector: quad_decimate must be in [1, 8]");
  if (!(settings.quad_sigma >= 0 && settings.quad_sigma <= 10))
    return Status::BadInput("library detector: quad_sigma must be in [0, 10] px");
  if (settings.bits_corrected < 0 || settings.bits_corrected > 3)
    return Status::BadInput("library detector: bits_corrected must be in 0..3");
  auto impl = std::make_unique<Impl>();
  impl->family = CreateAprilTagFamily(family);
  // Everything else as apriltag_detector_create leaves it: refine_edges 1,
  // decode_sharpening 0.25.
  impl->detector = apriltag_detector_create();
  apriltag_detector_add_family_bits(impl->detector, impl->family.get(), settings.bits_corrected);
  impl->detector->quad_decimate = static_cast<float>(settings.quad_decimate);
  impl->detector->quad_sigma = static_cast<float>(settings.quad_sigma);
  impl->detector->nthreads = settings.threads;
  return std::unique_ptr<LibraryDetector>(new LibraryDetector(std::move(impl)));
}

LibraryDetector::LibraryDetector(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LibraryDetector::~LibraryDetector() = default;

std::vector<DecodedTag> LibraryDetector::Detect(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1);
  // The library reads rows through `stride`; a cv::Mat row step is one.
  image_u8_t image{gray.cols, gray.rows, static_cast<int32_t>(gray.step[0]), const_cast<uint8_t*>(gray.data)};
  DetectionsPtr found(apriltag_detector_detect(impl_->detector, &image));
  std::vector<DecodedTag> tags;
  tags.reserve(static_cast<size_t>(zarray_size(found.get())));
  for (int i = 0; i < zarray_size(found.get()); ++i) {
    apriltag_detection_t* detection = nullptr;
    zarray_get(found.get(), i, &detection);
    DecodedTag tag;
    tag.id = detection->id;
    tag.hamming = detection->hamming;
    tag.decision_margin = detection->decision_margin;
    for (size_t k = 0; k < 4; ++k) {
      tag.corners[k] =
          Eigen::Vector2d(detection->p[k][0] + kAprilTagToOpenCv, detection->p[k][1] + kAprilTagToOpenCv);
    }
    tags.push_back(tag);
  }
  return tags;
}

}  // namespace hexcal

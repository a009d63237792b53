#include "vision/detection.h"

#include <apriltag/apriltag.h>

#include <algorithm>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "vision/edge_refine.h"
#include "vision/image_header.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

// AprilTag measures pixels from the top-left corner of the top-left pixel
// (its bilinear sampler reads pixel i at i + ½); OpenCV from that pixel's centre.
constexpr double kAprilTagToOpenCv = -0.5;
// Corners closer than this to the image's edge (pixels) are not trusted.
constexpr double kBorderPx = 1.0;

struct DetectionsDeleter {
  void operator()(zarray_t* detections) const { apriltag_detections_destroy(detections); }
};
using DetectionsPtr = std::unique_ptr<zarray_t, DetectionsDeleter>;

std::string FormatMargin(double margin) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(3);
  out << margin;
  return out.str();
}

}  // namespace

struct TagDetector::Impl {
  AprilTagFamilyPtr family;
  apriltag_detector_t* detector = nullptr;
  std::shared_ptr<const IdealPixelMap> ideal;
  int width_at_border = 0;

  ~Impl() {
    if (detector) {
      apriltag_detector_remove_family(detector, family.get());
      apriltag_detector_destroy(detector);
    }
  }

  DetectionsPtr Run(const cv::Mat& gray) {
    CV_Assert(gray.type() == CV_8UC1);
    // The library reads rows through `stride`; a cv::Mat row step is one.
    image_u8_t image{gray.cols, gray.rows, static_cast<int32_t>(gray.step[0]), const_cast<uint8_t*>(gray.data)};
    return DetectionsPtr(apriltag_detector_detect(detector, &image));
  }
};

bool DetectorOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!FindTagFamily(family)) return fail("family: '" + family + "' is not supported");
  if (threads < 1 || threads > 64) return fail("threads: must be in 1..64");
  if (!(min_decision_margin >= 0)) return fail("min_decision_margin: must be >= 0");
  if (max_hamming < 0 || max_hamming > 2) return fail("max_hamming: must be 0, 1 or 2");
  if (!(quad_sigma >= 0 && quad_sigma <= 10)) return fail("quad_sigma: must be in [0, 10] px");
  return true;
}

StatusOr<std::unique_ptr<TagDetector>> TagDetector::Create(const DetectorOptions& options,
                                                           std::shared_ptr<const IdealPixelMap> ideal) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("detector options: " + error);
  auto impl = std::make_unique<Impl>();
  impl->family = CreateAprilTagFamily(options.family);
  impl->width_at_border = impl->family->width_at_border;
  impl->ideal = std::move(ideal);
  impl->detector = apriltag_detector_create();
  // One corrected bit more than accepted, so that near misses are reported
  // as rejected rather than silently missing.
  apriltag_detector_add_family_bits(impl->detector, impl->family.get(), std::max(1, options.max_hamming));
  impl->detector->quad_decimate = 1;
  impl->detector->quad_sigma = static_cast<float>(options.quad_sigma);
  impl->detector->nthreads = options.threads;
  impl->detector->refine_edges = 1;
  return std::unique_ptr<TagDetector>(new TagDetector(options, std::move(impl)));
}

TagDetector::TagDetector(const DetectorOptions& options, std::unique_ptr<Impl> impl)
    : options_(options), impl_(std::move(impl)) {}

TagDetector::~TagDetector() = default;

int TagDetector::DetectWithLibraryOnly(const cv::Mat& gray) { return zarray_size(impl_->Run(gray).get()); }

Detections TagDetector::Detect(const cv::Mat& gray) {
  DetectionsPtr found = impl_->Run(gray);
  const IdealPixelMap* ideal = impl_->ideal.get();
  if (ideal && (ideal->width() != gray.cols || ideal->height() != gray.rows)) ideal = nullptr;
  Detections result;
  for (int i = 0; i < zarray_size(found.get()); ++i) {
    apriltag_detection_t* detection = nullptr;
    zarray_get(found.get(), i, &detection);
    if (detection->hamming > options_.max_hamming || detection->decision_margin < options_.min_decision_margin) {
      RejectedTag rejected{detection->id, detection->decision_margin, detection->hamming, ""};
      rejected.reason =
          detection->hamming > options_.max_hamming
              ? std::to_string(detection->hamming) + " corrected bits > " + std::to_string(options_.max_hamming)
              : "decision margin " + FormatMargin(detection->decision_margin) + " < " +
                    FormatMargin(options_.min_decision_margin);
      result.rejected.push_back(rejected);
      continue;
    }
    // A tag cut by the image border decodes, but the library extrapolates its
    // outer corners: keep only tags whose corners lie inside the image.
    bool inside = true;
    for (int k = 0; k < 4; ++k) {
      const double u = detection->p[k][0] + kAprilTagToOpenCv, v = detection->p[k][1] + kAprilTagToOpenCv;
      inside = inside && u >= kBorderPx && v >= kBorderPx && u <= gray.cols - 1 - kBorderPx &&
               v <= gray.rows - 1 - kBorderPx;
    }
    if (!inside) {
      result.rejected.push_back(
          {detection->id, detection->decision_margin, detection->hamming, "a corner is outside the image"});
      continue;
    }
    TagDetection tag;
    tag.id = detection->id;
    tag.decision_margin = detection->decision_margin;
    tag.hamming = detection->hamming;
    for (int k = 0; k < 4; ++k) {
      tag.corners[static_cast<size_t>(k)] =
          Eigen::Vector2d(detection->p[k][0] + kAprilTagToOpenCv, detection->p[k][1] + kAprilTagToOpenCv);
    }
    if (options_.refine_edges) {
      if (std::optional<RefinedTag> refined = RefineTagCorners(gray, ideal, impl_->width_at_border, tag.corners)) {
        tag.corners = refined->corners;
        tag.covariance = refined->covariance;
        tag.refined = true;
      }
    }
    result.tags.push_back(tag);
  }
  std::sort(result.tags.begin(), result.tags.end(),
            [](const TagDetection& a, const TagDetection& b) { return a.id < b.id; });
  return result;
}

BoardObservation MatchToTarget(const Target& target, const Detections& detections) {
  std::map<int, int> count;
  for (const TagDetection& tag : detections.tags) ++count[tag.id];
  BoardObservation observation;
  for (const TagDetection& tag : detections.tags) {
    if (!target.IndexOf(tag.id)) {
      ++observation.foreign_tags;
      continue;
    }
    if (count[tag.id] > 1) {
      ++observation.duplicate_tags;
      continue;
    }
    observation.tag_ids.push_back(tag.id);
    observation.corner_covariances.push_back(tag.covariance);
    const std::array<Eigen::Vector3d, 4> corners = target.TagCorners(tag.id);
    for (int k = 0; k < 4; ++k) {
      observation.target_points.push_back(corners[static_cast<size_t>(k)]);
      observation.image_points.push_back(tag.corners[static_cast<size_t>(k)]);
    }
  }
  return observation;
}

namespace {

// The checks made on the header before decoding; OK when the decoder may run.
Status CheckImageHeader(const ImageHeader& header, const std::string& source) {
  // imdecode tries every decoder OpenCV was built with (on Debian also DICOM,
  // JPEG 2000, OpenEXR, WebP ...), and some abort the process on a bad file
  // (GDCM's reader asserts: found by fuzz/image_fuzz). hexcal reads only
  // PNG, JPEG and TIFF, so nothing else reaches imdecode.
  if (header.format == ImageFormat::kOther) {
    return Status::Error(source + ": cannot decode: not a PNG, JPEG or TIFF file");
  }
  // Truncated files are caught here, before the decoders print their own
  // complaints on stderr.
  if (header.truncated && header.format == ImageFormat::kPng) {
    return Status::Error(source + ": truncated PNG (no IEND chunk)");
  }
  if (header.truncated) return Status::Error(source + ": truncated JPEG (no end-of-image marker)");
  if (!header.corrupt.empty()) return Status::Error(source + ": cannot decode: corrupt JPEG (" + header.corrupt + ")");
  // The decoder allocates what the header claims, however small the file.
  if (header.size && header.size->Pixels() > kMaxImagePixels) {
    return Status::Error(source + ": " + std::to_string(header.size->width) + " x " +
                         std::to_string(header.size->height) + " pixels is over the " +
                         std::to_string(kMaxImagePixels / 1'000'000) + "-megapixel limit");
  }
  return Status::Ok();
}

}  // namespace

StatusOr<cv::Mat> LoadGrayImage(const std::string& path) {
  StatusOr<std::string> bytes = ReadFileToString(path, kMaxImageBytes);
  if (!bytes.ok()) return bytes.status();
  return DecodeGrayImage(*bytes, path);
}

StatusOr<cv::Mat> DecodeGrayImage(const std::string& bytes, const std::string& source) {
  if (bytes.empty()) return Status::Error(source + ": empty file");
  const Status header = CheckImageHeader(ReadImageHeader(bytes), source);
  if (!header.ok()) return header;
  cv::Mat image;
  try {
    // imdecode only reads the buffer; the const_cast is what cv::Mat's constructor needs.
    const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
    image = cv::imdecode(buffer, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    return Status::Error(source + ": cannot decode: " + e.msg);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for a header claiming a huge image
    return Status::Error(source + ": cannot decode: " + e.what());
  }
  if (image.empty()) return Status::Error(source + ": cannot decode: corrupt, truncated or not an image");
  return image;
}

StatusOr<std::vector<std::unique_ptr<TagDetector>>> CreateWorkerDetectors(const DetectorOptions& options,
                                                                          std::shared_ptr<const IdealPixelMap> ideal,
                                                                          int workers) {
  DetectorOptions single = options;
  single.threads = 1;
  std::vector<std::unique_ptr<TagDetector>> detectors;
  for (int w = 0; w < workers; ++w) {
    StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(single, ideal);
    if (!detector.ok()) return detector.status();
    detectors.push_back(std::move(*detector));
  }
  return detectors;
}

}  // namespace hexcal

#include "vision/detection.h"

#include <apriltag/apriltag.h>

#include <algorithm>
#include <map>

#include "core/csv.h"
#include "vision/edge_refine.h"
#include "vision/quad_finder.h"
#include "vision/tag_decoder.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

// Corners closer than this to the image's edge (pixels) are not trusted.
constexpr double kBorderPx = 1.0;

struct DetectionsDeleter {
  void operator()(zarray_t* detections) const { apriltag_detections_destroy(detections); }
};
using DetectionsPtr = std::unique_ptr<zarray_t, DetectionsDeleter>;

}  // namespace

struct TagDetector::Impl {
  std::unique_ptr<QuadFinder> quads;
  TagCodebook codebook;
  std::shared_ptr<const IdealPixelMap> ideal;
  // The library's own detector, for DetectWithLibraryOnly (benchmarks) only.
  AprilTagFamilyPtr family;
  apriltag_detector_t* detector = nullptr;

  ~Impl() {
    if (detector) {
      apriltag_detector_remove_family(detector, family.get());
      apriltag_detector_destroy(detector);
    }
  }

  // Made on first use: only benchmarks call it.
  DetectionsPtr RunLibrary(const cv::Mat& gray, const DetectorOptions& options) {
    CV_Assert(gray.type() == CV_8UC1);
    if (!detector) {
      family = CreateAprilTagFamily(options.family);
      detector = apriltag_detector_create();
      apriltag_detector_add_family_bits(detector, family.get(), std::max(1, options.max_hamming));
      detector->quad_decimate = 1;
      detector->quad_sigma = static_cast<float>(options.quad_sigma);
      detector->nthreads = options.threads;
      detector->refine_edges = 1;
    }
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
  if (border_bits != 1 && border_bits != 2) return fail("border_bits: must be 1 or 2");
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
  StatusOr<TagCodebook> codebook = TagCodebook::Create(options.family, options.border_bits);
  if (!codebook.ok()) return Status::Error("detector options: " + codebook.status().message());
  StatusOr<std::unique_ptr<QuadFinder>> quads =
      QuadFinder::Create(options.threads, options.quad_sigma, codebook->width_at_border());
  if (!quads.ok()) return quads.status();
  auto impl = std::make_unique<Impl>();
  impl->quads = std::move(*quads);
  impl->codebook = std::move(*codebook);
  impl->ideal = std::move(ideal);
  return std::unique_ptr<TagDetector>(new TagDetector(options, std::move(impl)));
}

TagDetector::TagDetector(const DetectorOptions& options, std::unique_ptr<Impl> impl)
    : options_(options), impl_(std::move(impl)) {}

TagDetector::~TagDetector() = default;

int TagDetector::DetectWithLibraryOnly(const cv::Mat& gray) { return zarray_size(impl_->RunLibrary(gray, options_).get()); }

namespace {

bool CornersInside(const std::array<Eigen::Vector2d, 4>& corners, const cv::Mat& gray) {
  for (const Eigen::Vector2d& c : corners) {
    if (!(c.x() >= kBorderPx && c.y() >= kBorderPx && c.x() <= gray.cols - 1 - kBorderPx &&
          c.y() <= gray.rows - 1 - kBorderPx)) {
      return false;
    }
  }
  return true;
}

// Why a decode is not accepted, or "" when it is.
std::string RejectionReason(const DecodedTag& tag, const DetectorOptions& options, const cv::Mat& gray) {
  if (tag.hamming > options.max_hamming) {
    return std::to_string(tag.hamming) + " corrected bits > " + std::to_string(options.max_hamming);
  }
  if (tag.decision_margin < options.min_decision_margin) {
    return "decision margin " + FormatSignificant(tag.decision_margin) + " < " + FormatSignificant(options.min_decision_margin);
  }
  // A tag cut by the image border can still decode from its inner cells, but
  // its outer corners are extrapolated: keep only tags whose corners are inside.
  if (!CornersInside(tag.corners, gray)) return "a corner is outside the image";
  return "";
}

Eigen::Vector2d Centre(const std::array<Eigen::Vector2d, 4>& corners) {
  return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
}

// The same tag decoded from two quads (its outer edge and a ring just
// inside it): keep the decode with the fewer corrected bits, then the larger margin.
std::vector<DecodedTag> DropRepeatedDecodes(std::vector<DecodedTag> decoded) {
  std::sort(decoded.begin(), decoded.end(), [](const DecodedTag& a, const DecodedTag& b) {
    if (a.hamming != b.hamming) return a.hamming < b.hamming;
    return a.decision_margin > b.decision_margin;
  });
  std::vector<DecodedTag> kept;
  for (const DecodedTag& tag : decoded) {
    const double side = (tag.corners[1] - tag.corners[0]).norm();
    const bool repeated = std::any_of(kept.begin(), kept.end(), [&](const DecodedTag& other) {
      return other.id == tag.id && (Centre(other.corners) - Centre(tag.corners)).norm() < 0.25 * side;
    });
    if (!repeated) kept.push_back(tag);
  }
  return kept;
}

}  // namespace

Detections TagDetector::Detect(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1);
  const IdealPixelMap* ideal = impl_->ideal.get();
  if (ideal && (ideal->width() != gray.cols || ideal->height() != gray.rows)) ideal = nullptr;
  // One corrected bit more than accepted, so that near misses are reported
  // as rejected rather than silently missing.
  const int report_hamming = std::max(1, options_.max_hamming);
  std::vector<DecodedTag> decoded;
  for (const Quad& quad : impl_->quads->Find(gray)) {
    if (std::optional<DecodedTag> tag = impl_->codebook.Decode(gray, quad, report_hamming)) decoded.push_back(*tag);
  }
  Detections result;
  for (const DecodedTag& decode : DropRepeatedDecodes(std::move(decoded))) {
    const std::string reason = RejectionReason(decode, options_, gray);
    if (!reason.empty()) {
      result.rejected.push_back({decode.id, decode.decision_margin, decode.hamming, reason});
      continue;
    }
    TagDetection tag;
    tag.id = decode.id;
    tag.decision_margin = decode.decision_margin;
    tag.hamming = decode.hamming;
    tag.corners = decode.corners;
    if (options_.refine_edges) {
      if (std::optional<RefinedTag> refined =
              RefineTagCorners(gray, ideal, impl_->codebook.width_at_border(), impl_->codebook.border_bits(),
                               tag.corners, &tag.refine_failure)) {
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

DetectorOptions ForTarget(DetectorOptions options, const Target& target) {
  options.family = target.family;
  options.border_bits = target.border_bits;
  return options;
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

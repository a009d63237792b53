#include "vision/detection.h"

#include <algorithm>
#include <map>

#include "core/csv.h"
#include "vision/edge_refine.h"
#include "vision/library_detector.h"
#include "vision/quad_finder.h"
#include "vision/quad_snap.h"
#include "vision/tag_decoder.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

// Corners closer than this to the image's edge (pixels) are not trusted.
constexpr double kBorderPx = 1.0;
// The blur before the segmentation of the image as it is: sensor noise
// splits the thresholded image into many small components, and without it
// this pass alone took twice the rest of the detection (183 against 60 ms of
// CPU per bench render; the grown image is smoothed by its 3 × 3 maximum);
// a tag of 14 px keeps its 1.75 px border.
constexpr double kPlainPassSigmaPx = 0.8;

}  // namespace

struct TagDetector::Impl {
  std::unique_ptr<QuadFinder> grown_quads;  // white grown: aprilgrids' corner joints opened
  std::unique_ptr<QuadFinder> plain_quads;  // the image as it is (a little blurred): small tags' thin borders kept
  TagCodebook codebook;
  std::shared_ptr<const IdealPixelMap> ideal;
  // The library's default detector (vision/library_detector.h): the floor
  // under hexcal's tags; null when options.library_floor is off.
  std::unique_ptr<LibraryDetector> floor;
  // The library alone at hexcal's resolution, for DetectWithLibraryOnly
  // (benchmarks); made on first use.
  std::unique_ptr<LibraryDetector> benchmark_library;
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
  if (!options.IsValid(&error)) return Status::BadInput("detector options: " + error);
  StatusOr<TagCodebook> codebook = TagCodebook::Create(options.family, options.border_bits);
  if (!codebook.ok()) return Status::BadInput("detector options: " + codebook.status().message());
  StatusOr<std::unique_ptr<QuadFinder>> grown =
      QuadFinder::Create(options.threads, options.quad_sigma, codebook->width_at_border(), /*grow_white=*/true);
  if (!grown.ok()) return grown.status();
  StatusOr<std::unique_ptr<QuadFinder>> plain =
      QuadFinder::Create(options.threads, std::max(options.quad_sigma, kPlainPassSigmaPx), codebook->width_at_border(),
                         /*grow_white=*/false);
  if (!plain.ok()) return plain.status();
  auto impl = std::make_unique<Impl>();
  impl->grown_quads = std::move(*grown);
  impl->plain_quads = std::move(*plain);
  impl->codebook = std::move(*codebook);
  impl->ideal = std::move(ideal);
  if (options.library_floor) {
    LibraryDetectorSettings settings;
    settings.threads = options.threads;
    StatusOr<std::unique_ptr<LibraryDetector>> floor = LibraryDetector::Create(options.family, settings);
    if (!floor.ok()) return floor.status();
    impl->floor = std::move(*floor);
  }
  return std::unique_ptr<TagDetector>(new TagDetector(options, std::move(impl)));
}

TagDetector::TagDetector(const DetectorOptions& options, std::unique_ptr<Impl> impl)
    : options_(options), impl_(std::move(impl)) {}

TagDetector::~TagDetector() = default;

int TagDetector::DetectWithLibraryOnly(const cv::Mat& gray) {
  if (!impl_->benchmark_library) {
    LibraryDetectorSettings settings;
    settings.quad_decimate = 1;
    settings.quad_sigma = options_.quad_sigma;
    settings.bits_corrected = std::max(1, options_.max_hamming);
    settings.threads = options_.threads;
    impl_->benchmark_library = LibraryDetector::Create(options_.family, settings).value();
  }
  return static_cast<int>(impl_->benchmark_library->Detect(gray).size());
}

namespace {

// Whether the tag's corners, and the ring of white cells around its black
// square, lie in the image. A tag cut by the border decodes from its inner
// cells; the segmentation of the image as it is then closes its quad along
// the border, 1-2 px inside it, where no white ring is seen.
bool RingInside(const std::array<Eigen::Vector2d, 4>& corners, int width_at_border, const cv::Mat& gray) {
  double perimeter = 0;
  for (size_t k = 0; k < 4; ++k) perimeter += (corners[(k + 1) % 4] - corners[k]).norm();
  const double margin = std::max(kBorderPx, perimeter / 4 / width_at_border);
  for (const Eigen::Vector2d& c : corners) {
    if (!(c.x() >= margin && c.y() >= margin && c.x() <= gray.cols - 1 - margin && c.y() <= gray.rows - 1 - margin)) {
      return false;
    }
  }
  return true;
}

// Why a decode is not accepted, or "" when it is.
std::string RejectionReason(const DecodedTag& tag, const DetectorOptions& options, int width_at_border,
                            const cv::Mat& gray) {
  if (tag.hamming > options.max_hamming) {
    return std::to_string(tag.hamming) + " corrected bits > " + std::to_string(options.max_hamming);
  }
  if (tag.decision_margin < options.min_decision_margin) {
    return "decision margin " + FormatSignificant(tag.decision_margin) + " < " + FormatSignificant(options.min_decision_margin);
  }
  // A tag cut by the image border can still decode from its inner cells, but
  // its outer corners are extrapolated or lie on the border.
  if (!RingInside(tag.corners, width_at_border, gray)) return "a corner is outside the image";
  return "";
}

Eigen::Vector2d Centre(const std::array<Eigen::Vector2d, 4>& corners) {
  return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
}

// Where a decode's quad came from, in the order of preference between two
// decodes of one tag with as many corrected bits: the image's own quad fit
// (the library's at full resolution), the grown-white one (its erosion undone
// exactly only for straight, sharp edges), the library's at half resolution.
enum class QuadSource { kImage = 0, kGrownWhite = 1, kLibrary = 2 };

struct Candidate {
  DecodedTag tag;
  QuadSource source = QuadSource::kImage;
};

// Whether p lies inside the convex quad (either winding).
bool Inside(const std::array<Eigen::Vector2d, 4>& corners, const Eigen::Vector2d& p) {
  int positive = 0, negative = 0;
  for (size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d edge = corners[(k + 1) % 4] - corners[k], to_p = p - corners[k];
    const double cross = edge.x() * to_p.y() - edge.y() * to_p.x();
    positive += cross > 0;
    negative += cross < 0;
  }
  return positive == 0 || negative == 0;
}

// A quad well inside a tag already decoded (a data cell's blob, a ring of the
// border) cannot be another tag, and decoding is the costly part: skip it.
// Quads of about the tag's size are decoded again (another fit of its edge).
bool InsideADecodedTag(const Quad& quad, const std::vector<Candidate>& candidates) {
  const Eigen::Vector2d centre = Centre(quad.corners);
  const double area = std::abs(SignedArea(quad.corners));
  return std::any_of(candidates.begin(), candidates.end(), [&](const Candidate& c) {
    return area < 0.7 * std::abs(SignedArea(c.tag.corners)) && Inside(c.tag.corners, centre);
  });
}

void DecodeQuads(const cv::Mat& gray, std::vector<Quad> quads, QuadSource source, const TagCodebook& codebook,
                 int max_hamming, std::vector<Candidate>& candidates) {
  // Largest first: a tag's outer edge before the blobs inside it.
  std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) {
    return std::abs(SignedArea(a.corners)) > std::abs(SignedArea(b.corners));
  });
  for (const Quad& quad : quads) {
    if (InsideADecodedTag(quad, candidates)) continue;
    // The snapped quad reads most tags best; a few of 14 px read only
    // through the quad as found.
    std::optional<DecodedTag> tag = codebook.Decode(gray, SnapQuadEdges(gray, quad), max_hamming);
    if (!tag) tag = codebook.Decode(gray, quad, max_hamming);
    if (tag) candidates.push_back({*tag, source});
  }
}

// The library's default detector's tags (vision/library_detector.h). It reads
// the one-cell layout; for a target with two, its quad is kept only where
// hexcal's codebook reads the same tag in it.
void AddLibraryTags(const cv::Mat& gray, LibraryDetector& library, const TagCodebook& codebook, int max_hamming,
                    std::vector<Candidate>& candidates) {
  for (const DecodedTag& tag : library.Detect(gray)) {
    if (codebook.border_bits() == 1) {
      candidates.push_back({tag, QuadSource::kLibrary});
      continue;
    }
    Quad quad{tag.corners};
    if (SignedArea(quad.corners) > 0) std::swap(quad.corners[1], quad.corners[3]);
    std::optional<DecodedTag> again = codebook.Decode(gray, SnapQuadEdges(gray, quad), max_hamming);
    if (again && again->id == tag.id) candidates.push_back({*again, QuadSource::kLibrary});
  }
}

// Whether the candidates so far hold an accepted decode of every tag in
// options.expected_ids (none expected: false, every pass runs).
bool EveryExpectedTagAccepted(const std::vector<Candidate>& candidates, const DetectorOptions& options,
                              int width_at_border, const cv::Mat& gray) {
  if (options.expected_ids.empty()) return false;
  std::vector<int> accepted;
  for (const Candidate& c : candidates)
    if (RejectionReason(c.tag, options, width_at_border, gray).empty()) accepted.push_back(c.tag.id);
  std::sort(accepted.begin(), accepted.end());
  return std::all_of(options.expected_ids.begin(), options.expected_ids.end(),
                     [&](int id) { return std::binary_search(accepted.begin(), accepted.end(), id); });
}

// The same tag decoded from several quads (the passes above, or its outer
// edge and a ring just inside it): keep the decode with the fewer corrected
// bits, then the preferred source, then the larger margin.
std::vector<DecodedTag> DropRepeatedDecodes(std::vector<Candidate> candidates) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.tag.hamming != b.tag.hamming) return a.tag.hamming < b.tag.hamming;
    if (a.source != b.source) return a.source < b.source;
    return a.tag.decision_margin > b.tag.decision_margin;
  });
  std::vector<DecodedTag> kept;
  for (const Candidate& candidate : candidates) {
    const DecodedTag& tag = candidate.tag;
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
  std::vector<Candidate> candidates;
  if (impl_->floor) AddLibraryTags(gray, *impl_->floor, impl_->codebook, report_hamming, candidates);
  if (!EveryExpectedTagAccepted(candidates, options_, impl_->codebook.width_at_border(), gray)) {
    DecodeQuads(gray, impl_->plain_quads->Find(gray), QuadSource::kImage, impl_->codebook, report_hamming,
                candidates);
    DecodeQuads(gray, impl_->grown_quads->Find(gray), QuadSource::kGrownWhite, impl_->codebook, report_hamming,
                candidates);
  }
  Detections result;
  for (const DecodedTag& decode : DropRepeatedDecodes(std::move(candidates))) {
    const std::string reason = RejectionReason(decode, options_, impl_->codebook.width_at_border(), gray);
    if (!reason.empty()) {
      result.rejected.push_back({decode.id, decode.decision_margin, decode.hamming, reason});
      continue;
    }
    TagDetection tag;
    tag.id = decode.id;
    tag.decision_margin = decode.decision_margin;
    tag.hamming = decode.hamming;
    // Every pass's quad moved onto the image's edges (vision/quad_snap.h).
    tag.corners = SnapQuadEdges(gray, Quad{decode.corners}).corners;
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
  options.expected_ids = target.TagIds();
  std::sort(options.expected_ids.begin(), options.expected_ids.end());
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

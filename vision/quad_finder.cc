#include "vision/quad_finder.h"

#include <apriltag/apriltag.h>

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "vision/tag_family.h"

// Exported by libapriltag 3.3 (its quad stage, which apriltag_detector_detect
// runs before decoding) but declared in no installed header; `struct quad`
// is in apriltag.h.
extern "C" zarray_t* apriltag_quad_thresh(apriltag_detector_t* td, image_u8_t* im);

namespace hexcal {
namespace {

// AprilTag measures pixels from the top-left corner of the top-left pixel;
// OpenCV from that pixel's centre (docs/conventions.md).
constexpr double kAprilTagToOpenCv = -0.5;
// The grey maximum that opens the corner joints of an aprilgrid: 3 × 3.
constexpr int kGrowthRadius = 1;

struct QuadListDeleter {
  void operator()(zarray_t* quads) const { zarray_destroy(quads); }
};
using QuadListPtr = std::unique_ptr<zarray_t, QuadListDeleter>;

// The line through a and b moved by `shift` along its normal away from `centre`,
// as (unit normal n, offset c) with n · p = c.
std::pair<Eigen::Vector2d, double> ShiftedLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                               const Eigen::Vector2d& centre, double radius) {
  const Eigen::Vector2d along = (b - a).normalized();
  Eigen::Vector2d n(-along.y(), along.x());
  if (n.dot(a - centre) < 0) n = -n;
  const double shift = radius * (std::abs(n.x()) + std::abs(n.y()));
  return {n, n.dot(a) + shift};
}

}  // namespace

double SignedArea(const std::array<Eigen::Vector2d, 4>& corners) {
  double twice = 0;
  for (size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d& p = corners[k];
    const Eigen::Vector2d& q = corners[(k + 1) % 4];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

std::array<Eigen::Vector2d, 4> UndoWhiteGrowth(const std::array<Eigen::Vector2d, 4>& corners, double radius) {
  const Eigen::Vector2d centre = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
  std::array<std::pair<Eigen::Vector2d, double>, 4> lines;  // edge k runs from corner k to k + 1
  for (size_t k = 0; k < 4; ++k) lines[k] = ShiftedLine(corners[k], corners[(k + 1) % 4], centre, radius);
  std::array<Eigen::Vector2d, 4> moved = corners;
  for (size_t k = 0; k < 4; ++k) {
    // Corner k is where edge k - 1 meets edge k.
    const auto& [n1, c1] = lines[(k + 3) % 4];
    const auto& [n2, c2] = lines[k];
    Eigen::Matrix2d normals;
    normals << n1.transpose(), n2.transpose();
    if (std::abs(normals.determinant()) < 1e-9) continue;
    moved[k] = normals.inverse() * Eigen::Vector2d(c1, c2);
  }
  return moved;
}

struct QuadFinder::Impl {
  AprilTagFamilyPtr family;  // only its width and border colour matter to the quad fit
  apriltag_detector_t* detector = nullptr;
  double quad_sigma = 0;
  bool grow_white = true;

  ~Impl() {
    if (detector) {
      apriltag_detector_remove_family(detector, family.get());
      apriltag_detector_destroy(detector);
    }
  }
};

StatusOr<std::unique_ptr<QuadFinder>> QuadFinder::Create(int threads, double quad_sigma, int min_width_cells,
                                                         bool grow_white) {
  if (threads < 1 || threads > 64) return Status::BadInput("quad finder: threads must be in 1..64");
  if (!(quad_sigma >= 0 && quad_sigma <= 10)) return Status::BadInput("quad finder: quad_sigma must be in [0, 10] px");
  auto impl = std::make_unique<Impl>();
  impl->family = CreateAprilTagFamily("tag16h5");  // the smallest table; its codes are never used
  impl->family->width_at_border = static_cast<uint32_t>(std::max(min_width_cells, 3));
  impl->detector = apriltag_detector_create();
  apriltag_detector_add_family_bits(impl->detector, impl->family.get(), 0);
  impl->detector->quad_decimate = 1;
  impl->detector->nthreads = threads;
  impl->quad_sigma = quad_sigma;
  impl->grow_white = grow_white;
  // The library makes its worker pool in its first detection; apriltag_quad_thresh
  // needs that pool, so run one on a blank image now.
  uint8_t blank[16 * 16] = {};
  image_u8_t image{16, 16, 16, blank};
  apriltag_detections_destroy(apriltag_detector_detect(impl->detector, &image));
  return std::unique_ptr<QuadFinder>(new QuadFinder(std::move(impl)));
}

QuadFinder::QuadFinder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
QuadFinder::~QuadFinder() = default;

std::vector<Quad> QuadFinder::Find(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1);
  cv::Mat grown;
  if (impl_->grow_white) {
    cv::dilate(gray, grown, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * kGrowthRadius + 1, 2 * kGrowthRadius + 1)));
  } else {
    grown = impl_->quad_sigma > 0 ? gray.clone() : gray;
  }
  if (impl_->quad_sigma > 0) cv::GaussianBlur(grown, grown, cv::Size(), impl_->quad_sigma);
  image_u8_t image{grown.cols, grown.rows, static_cast<int32_t>(grown.step[0]), grown.data};
  QuadListPtr found(apriltag_quad_thresh(impl_->detector, &image));
  std::vector<Quad> quads;
  quads.reserve(static_cast<size_t>(zarray_size(found.get())));
  for (int i = 0; i < zarray_size(found.get()); ++i) {
    struct quad* q = nullptr;
    zarray_get_volatile(found.get(), i, &q);
    Quad quad;
    for (size_t k = 0; k < 4; ++k) {
      quad.corners[k] = Eigen::Vector2d(q->p[k][0] + kAprilTagToOpenCv, q->p[k][1] + kAprilTagToOpenCv);
    }
    if (SignedArea(quad.corners) > 0) std::swap(quad.corners[1], quad.corners[3]);
    if (impl_->grow_white) quad.corners = UndoWhiteGrowth(quad.corners, kGrowthRadius);
    quads.push_back(quad);
  }
  return quads;
}

}  // namespace hexcal

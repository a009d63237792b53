#include "vision/target_coverage.h"

#include <algorithm>
#include <cmath>

namespace hexcal {
namespace {

constexpr int kMaxVertices = 16;  // 4 + one per clipping half-plane, with room

// Keeps the part of polygon `in` where sign * (p[axis] - bound) <= 0.
int ClipHalfPlane(const Eigen::Vector2d* in, int count, int axis, double bound, double sign, Eigen::Vector2d* out) {
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % count];
    const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
    if (da <= 0) out[n++] = a;
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out[n++] = a + (b - a) * (da / (da - db));
  }
  return n;
}

}  // namespace

double PolygonArea(const Eigen::Vector2d* polygon, int count) {
  double twice = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % count];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

double ClippedArea(const Eigen::Vector2d* polygon, int count, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  Eigen::Vector2d a[kMaxVertices], b[kMaxVertices];
  int n = ClipHalfPlane(polygon, count, 0, lo.x(), -1, a);
  n = ClipHalfPlane(a, n, 0, hi.x(), 1, b);
  n = ClipHalfPlane(b, n, 1, lo.y(), -1, a);
  n = ClipHalfPlane(a, n, 1, hi.y(), 1, b);
  return n < 3 ? 0 : PolygonArea(b, n);
}

TargetPattern::TargetPattern(const Target& target)
    : target_(target), cells_(TagCellsOf(target.family, target.TagIds(), target.border_bits)) {
  cell_ = target.tag_size / target.WidthAtBorder();
  ring_ = 1;  // the white ring of TagCells around the black square
  const Eigen::Vector2d tags_min = target.TagsMin();
  sheet_min_ = tags_min - Eigen::Vector2d::Constant(target.margin);
  sheet_max_ = tags_min + Eigen::Vector2d(target.Width(), target.Height()) + Eigen::Vector2d::Constant(target.margin);
  // A bucket as large as a tag's cell grid: each tag meets at most 2 × 2.
  const double reach = ring_ * cell_;
  bucket_size_ = target.tag_size + 2 * reach;
  bucket_min_ = tags_min - Eigen::Vector2d::Constant(reach);
  bucket_cols_ = static_cast<int>(std::floor((target.Width() + 2 * reach) / bucket_size_)) + 1;
  bucket_rows_ = static_cast<int>(std::floor((target.Height() + 2 * reach) / bucket_size_)) + 1;
  buckets_.resize(static_cast<size_t>(bucket_cols_ * bucket_rows_));
  for (int index = 0; index < target.NumTags(); ++index) {
    origins_.push_back(target.TagOrigin(index));
    const Eigen::Vector2d lo = (origins_.back() - Eigen::Vector2d::Constant(reach) - bucket_min_) / bucket_size_;
    const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(1);
    for (int row = std::max(0, static_cast<int>(std::floor(lo.y())));
         row <= std::min(bucket_rows_ - 1, static_cast<int>(std::floor(hi.y()))); ++row) {
      for (int col = std::max(0, static_cast<int>(std::floor(lo.x())));
           col <= std::min(bucket_cols_ - 1, static_cast<int>(std::floor(hi.x()))); ++col) {
        buckets_[static_cast<size_t>(row * bucket_cols_ + col)].push_back(index);
      }
    }
  }
}

void TargetPattern::TagsNear(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::vector<int>* indices) const {
  indices->clear();
  const Eigen::Vector2d a = (lo - bucket_min_) / bucket_size_, b = (hi - bucket_min_) / bucket_size_;
  if (!(b.x() >= 0 && b.y() >= 0 && a.x() < bucket_cols_ && a.y() < bucket_rows_)) return;  // NaN too
  const int c0 = std::max(0, static_cast<int>(std::floor(a.x())));
  const int c1 = std::min(bucket_cols_ - 1, static_cast<int>(std::floor(b.x())));
  const int r0 = std::max(0, static_cast<int>(std::floor(a.y())));
  const int r1 = std::min(bucket_rows_ - 1, static_cast<int>(std::floor(b.y())));
  for (int row = r0; row <= r1; ++row) {
    for (int col = c0; col <= c1; ++col) {
      const std::vector<int>& bucket = buckets_[static_cast<size_t>(row * bucket_cols_ + col)];
      indices->insert(indices->end(), bucket.begin(), bucket.end());
    }
  }
  std::sort(indices->begin(), indices->end());
  indices->erase(std::unique(indices->begin(), indices->end()), indices->end());
}

bool TargetPattern::IsBlackAt(const Eigen::Vector2d& p) const {
  thread_local std::vector<int> near;
  TagsNear(p, p, &near);
  for (const int index : near) {
    const Eigen::Vector2d& o = origins_[static_cast<size_t>(index)];
    // Cell (i, j) of the total_width grid: i counts down from the top.
    const int j = static_cast<int>(std::floor((p.x() - o.x()) / cell_)) + ring_;
    const int i = static_cast<int>(std::floor((o.y() + target_.tag_size - p.y()) / cell_)) + ring_;
    const TagCells& tag = cells_[static_cast<size_t>(index)];
    if (i >= 0 && j >= 0 && i < tag.total_width && j < tag.total_width && tag.IsBlack(i, j)) return true;
  }
  return false;
}

double TargetPattern::BlackAreaInTag(const std::array<Eigen::Vector2d, 4>& quad, const Eigen::Vector2d& lo,
                                     const Eigen::Vector2d& hi, int index) const {
  const TagCells& tag = cells_[static_cast<size_t>(index)];
  const Eigen::Vector2d& o = origins_[static_cast<size_t>(index)];
  const double top = o.y() + target_.tag_size + ring_ * cell_;  // y of the grid's top edge
  const double left = o.x() - ring_ * cell_;
  const int n = tag.total_width;
  const int j0 = std::max(0, static_cast<int>(std::floor((lo.x() - left) / cell_)));
  const int j1 = std::min(n - 1, static_cast<int>(std::floor((hi.x() - left) / cell_)));
  const int i0 = std::max(0, static_cast<int>(std::floor((top - hi.y()) / cell_)));
  const int i1 = std::min(n - 1, static_cast<int>(std::floor((top - lo.y()) / cell_)));
  double area = 0;
  for (int i = i0; i <= i1; ++i) {
    for (int j = j0; j <= j1; ++j) {
      if (!tag.IsBlack(i, j)) continue;
      const Eigen::Vector2d cell_lo(left + j * cell_, top - (i + 1) * cell_);
      const Eigen::Vector2d cell_hi(left + (j + 1) * cell_, top - i * cell_);
      if (lo.x() >= cell_lo.x() && hi.x() <= cell_hi.x() && lo.y() >= cell_lo.y() && hi.y() <= cell_hi.y()) {
        return PolygonArea(quad.data(), 4);  // wholly inside one black cell
      }
      area += ClippedArea(quad.data(), 4, cell_lo, cell_hi);
    }
  }
  return area;
}

TargetPattern::Coverage TargetPattern::Cover(const std::array<Eigen::Vector2d, 4>& quad) const {
  Eigen::Vector2d lo = quad[0], hi = quad[0];
  for (const Eigen::Vector2d& p : quad) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double total = PolygonArea(quad.data(), 4);
  Coverage coverage;
  if (!(total > 0) || !std::isfinite(total)) {  // degenerate footprint: sample its centre
    const Eigen::Vector2d c = 0.25 * (quad[0] + quad[1] + quad[2] + quad[3]);
    coverage.sheet = (c.array() >= sheet_min_.array()).all() && (c.array() <= sheet_max_.array()).all();
    coverage.black = IsBlackAt(c) ? 1 : 0;
    return coverage;
  }
  if ((lo.array() >= sheet_min_.array()).all() && (hi.array() <= sheet_max_.array()).all()) {
    coverage.sheet = 1;
  } else if ((hi.array() < sheet_min_.array()).any() || (lo.array() > sheet_max_.array()).any()) {
    return coverage;  // wholly off the sheet
  } else {
    coverage.sheet = std::min(1.0, ClippedArea(quad.data(), 4, sheet_min_, sheet_max_) / total);
  }
  thread_local std::vector<int> near;
  TagsNear(lo, hi, &near);
  double black = 0;
  for (const int index : near) black += BlackAreaInTag(quad, lo, hi, index);
  coverage.black = std::min(coverage.sheet, black / total);
  return coverage;
}

}  // namespace hexcal

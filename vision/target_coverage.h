// The printed pattern of a target as exact areas: how much of a small polygon
// on the target plane is sheet, and how much of it is black. The renderer and
// the printable target both draw with it, so an edge lands where the geometry
// puts it, to the precision of a double, at any pose or print resolution.
//
//   TargetPattern pattern(target);
//   TargetPattern::Coverage c = pattern.Cover(pixel_footprint_in_target);
//   double grey = background * (1 - c.sheet) + white * (c.sheet - c.black) + black * c.black;
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "vision/tag_family.h"
#include "vision/target.h"

namespace hexcal {

class TargetPattern {
 public:
  explicit TargetPattern(const Target& target);  // target must be valid

  struct Coverage {
    double sheet = 0;  // fraction of the polygon on the sheet, [0, 1]
    double black = 0;  // fraction on black cells, [0, sheet]
  };
  // `quad`: a convex quadrilateral in target-frame (x, y), either orientation.
  Coverage Cover(const std::array<Eigen::Vector2d, 4>& quad) const;

  // The sheet: [min, max] in target-frame x and y.
  Eigen::Vector2d SheetMin() const { return sheet_min_; }
  Eigen::Vector2d SheetMax() const { return sheet_max_; }
  bool IsBlackAt(const Eigen::Vector2d& p) const;

 private:
  // Black area of `quad` (already known to intersect tag `index`'s cells).
  double BlackAreaInTag(const std::array<Eigen::Vector2d, 4>& quad, const Eigen::Vector2d& lo,
                        const Eigen::Vector2d& hi, int index) const;
  // Indices, ascending, of the tags whose cell grid (black square and white
  // ring) may meet the box [lo, hi].
  void TagsNear(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::vector<int>* indices) const;

  Target target_;
  std::vector<TagCells> cells_;
  std::vector<Eigen::Vector2d> origins_;  // by tag index
  double cell_ = 0;  // cell edge, length unit
  int ring_ = 0;     // cells between the total_width grid's edge and the black square
  Eigen::Vector2d sheet_min_, sheet_max_;
  // Buckets of bucket_size_ squares from bucket_min_, row-major: the tags
  // whose cell grid meets each, so that a lookup is quick for any layout.
  Eigen::Vector2d bucket_min_;
  double bucket_size_ = 1;
  int bucket_cols_ = 0, bucket_rows_ = 0;
  std::vector<std::vector<int>> buckets_;
};

// Area of the part of `polygon` inside [lo, hi] (Sutherland–Hodgman clip).
double ClippedArea(const Eigen::Vector2d* polygon, int count, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);
double PolygonArea(const Eigen::Vector2d* polygon, int count);  // unsigned

}  // namespace hexcal

// Candidate tag quads in a grey image: the AprilTag library's segmentation and
// quad fit (apriltag_quad_thresh), run on a copy of the image whose white is
// grown by one pixel.
//
// Why grown: on a Kalibr aprilgrid a small black square sits in every gap
// crossing and touches four tags at their corners. Thresholded, it joins the
// tags' black borders, so the white around a tag falls apart into four strips
// and the library never sees a closed quad (0 tags on every real aprilgrid
// photo). A 3 × 3 grey maximum opens those one-point joints; the quad found in
// it is then pushed back out by the support of the 3 × 3 square,
// |n_x| + |n_y| pixels along each edge's normal n, which undoes the erosion of
// the black square exactly for straight edges (docs/vision.md, "Finding tags
// on real photographs").
//
//   StatusOr<std::unique_ptr<QuadFinder>> finder = QuadFinder::Create(/*threads=*/2, /*quad_sigma=*/0);
//   std::vector<Quad> quads = (*finder)->Find(gray);
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/status.h"

namespace hexcal {

// Corners in OpenCV's pixel convention, in the order that runs
// counter-clockwise on the screen (bottom-left, bottom-right, top-right,
// top-left of an upright square): a camera never sees a tag mirrored, so
// only the four rotations of this order remain to be decoded.
struct Quad {
  std::array<Eigen::Vector2d, 4> corners;
};

// Signed area of a polygon by the shoelace formula, pixels²; negative for
// the screen-counter-clockwise order of Quad.
double SignedArea(const std::array<Eigen::Vector2d, 4>& corners);

// The corners of a quad found in an image whose white was grown by a
// (2 radius + 1)² square: each edge moved out by radius · (|n_x| + |n_y|).
// nullopt-free: parallel neighbouring edges (never a quad) keep their corner.
std::array<Eigen::Vector2d, 4> UndoWhiteGrowth(const std::array<Eigen::Vector2d, 4>& corners, double radius);

class QuadFinder {
 public:
  // `threads`: the library's workers for one image; `quad_sigma`: Gaussian
  // blur before segmentation, px (0 = none); `min_width_cells`: the cells across
  // the smallest tag's black square (the library skips quads too small to hold one);
  // `grow_white`: false finds the quads of the image as it is, as the library does.
  static StatusOr<std::unique_ptr<QuadFinder>> Create(int threads, double quad_sigma, int min_width_cells,
                                                      bool grow_white = true);
  ~QuadFinder();
  QuadFinder(const QuadFinder&) = delete;
  QuadFinder& operator=(const QuadFinder&) = delete;

  // `gray`: CV_8UC1. Every quad, whether or not a tag is inside.
  std::vector<Quad> Find(const cv::Mat& gray);

 private:
  struct Impl;
  explicit QuadFinder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hexcal

// Reading a quad as a tag: the bits of every tag of a family, with a black
// border one or two cells wide, and the decode of a quad found in an image.
//
// The AprilTag library decodes only the border its family tables were made
// for (one cell); Kalibr prints its aprilgrid with two. Here the quad's
// homography samples the centre of every cell of the black square (W = data
// width + 2 × border cells across it), and the threshold at each data cell is
// the mean of a black and a white grey model, each a plane a + b x + c y
// fitted to the border cells and to the white ring outside them (its corner
// cells left out: an aprilgrid's corner squares sit there). The cell values
// are sharpened as the library does (value += 0.25 × the 4-neighbour
// Laplacian of value − threshold), then compared with every code in its four
// rotations. The decision margin is the library's: the smaller of the mean
// distances from the threshold of the cells read white and of those read black.
//
//   StatusOr<TagCodebook> codebook = TagCodebook::Create("tag36h11", /*border_bits=*/2);
//   std::optional<DecodedTag> tag = codebook->Decode(gray, quad, /*max_hamming=*/1);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "vision/quad_finder.h"

namespace hexcal {

struct DecodedTag {
  int id = 0;
  int hamming = 0;             // bits that differ from the code
  double decision_margin = 0;  // grey levels
  // The quad's corners in the AprilTag order: bottom-left, bottom-right,
  // top-right, top-left of the tag as printed upright.
  std::array<Eigen::Vector2d, 4> corners;
};

class TagCodebook {
 public:
  // `border_bits`: 1 (the AprilTag library's tags) or 2 (Kalibr's aprilgrid).
  static StatusOr<TagCodebook> Create(const std::string& family, int border_bits);

  int border_bits() const { return border_bits_; }
  int data_width() const { return data_width_; }
  // Cells across the black square: data width + 2 × border bits.
  int width_at_border() const { return data_width_ + 2 * border_bits_; }

  // The best code within `max_hamming` bits, or nullopt (not a tag, or a
  // cell outside the image). `gray`: CV_8UC1.
  std::optional<DecodedTag> Decode(const cv::Mat& gray, const Quad& quad, int max_hamming) const;

 private:
  struct Reading {
    uint64_t bits = 0;  // data cells row by row from the top left, 1 = black
    double decision_margin = 0;
  };
  std::optional<Reading> Read(const cv::Mat& gray, const std::array<Eigen::Vector2d, 4>& corners) const;

  int border_bits_ = 1;
  int data_width_ = 0;
  std::vector<uint64_t> codes_;  // by id, in Reading's bit order
};

}  // namespace hexcal

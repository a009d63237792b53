// Why an image shows (almost) none of the target's tags: the tags it does
// hold, read with the other border width or another family. The usual cause
// of an empty Kalibr aprilgrid is a target file with border_bits 1 (hexcal's
// names) for a board printed with two; of an empty board, a family other
// than the file's.
//
//   if (std::optional<LayoutHint> hint = BetterLayout(gray, options, found.tags.size()))
//     std::cerr << DescribeLayoutHint(*hint, options) << "\n";  // "14 tags with border_bits 2 (...)"
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "vision/detection.h"

namespace hexcal {

struct LayoutHint {
  std::string family;
  int border_bits = 1;
  int tags = 0;  // accepted tags with that family and border
};

// The family and border (other than `options`') that find the most tags in
// `gray`, when that is at least 4 and more than `found`; nullopt otherwise,
// and when `found` is already 4 or more (the layout is right).
std::optional<LayoutHint> BetterLayout(const cv::Mat& gray, const DetectorOptions& options, size_t found);

// "14 tags with border_bits 2 (--border-bits, or the target file's key)" or
// "9 tags of family tag25h9 (the target file's family key)".
std::string DescribeLayoutHint(const LayoutHint& hint, const DetectorOptions& options);

}  // namespace hexcal

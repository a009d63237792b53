// The grey value of an 8-bit image between pixel centres, by bilinear
// interpolation, OpenCV's pixel convention ((0, 0) the centre of the top-left
// pixel); nullopt outside the image. Shared by the decoder's cell sampling
// (vision/tag_decoder.h) and the edge snap (vision/quad_snap.h).
//
//   std::optional<double> grey = BilinearGrey(gray, 12.25, 40.5);
#pragma once

#include <algorithm>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>

namespace hexcal {

inline std::optional<double> BilinearGrey(const cv::Mat& gray, double u, double v) {
  if (!(u >= 0 && v >= 0 && u <= gray.cols - 1 && v <= gray.rows - 1)) return std::nullopt;
  const int u0 = std::min(static_cast<int>(u), gray.cols - 2), v0 = std::min(static_cast<int>(v), gray.rows - 2);
  const double fu = u - u0, fv = v - v0;
  const uint8_t* row0 = gray.ptr<uint8_t>(v0);
  const uint8_t* row1 = gray.ptr<uint8_t>(v0 + 1);
  return (1 - fv) * ((1 - fu) * row0[u0] + fu * row0[u0 + 1]) + fv * ((1 - fu) * row1[u0] + fu * row1[u0 + 1]);
}

}  // namespace hexcal

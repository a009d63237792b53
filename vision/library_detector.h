// The AprilTag library's own detector, with its default settings, as the
// floor under hexcal's detection.
//
// hexcal finds quads on the image (slightly blurred) and on the image whose
// white is grown by one pixel (so that the corner squares of an aprilgrid do
// not close the white around a tag, vision/quad_finder.h), and decodes them
// with its own codebook (one- or two-cell borders, vision/tag_decoder.h).
// Neither pass is the library's own detection: tiny tags in JPEG noise are
// found by its segmentation at half resolution and not at full. So
// TagDetector also runs the library exactly as `apriltag_detector_create`
// sets it up (quad_decimate 2, no blur, edge
// refinement, decode sharpening 0.25, two corrected bits) and keeps every tag
// it finds that hexcal's passes missed: hexcal never finds fewer tags than the
// library (docs/vision.md, "The library as the floor").
//
//   StatusOr<std::unique_ptr<LibraryDetector>> library = LibraryDetector::Create("tag36h11");
//   std::vector<DecodedTag> tags = (*library)->Detect(gray);  // OpenCV pixel convention
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "vision/tag_decoder.h"

namespace hexcal {

struct LibraryDetectorSettings {
  double quad_decimate = 2;  // the library's default: quads found at half resolution
  double quad_sigma = 0;     // the library's default: no blur before segmentation, px
  int bits_corrected = 2;    // the library's default for apriltag_detector_add_family
  int threads = 1;           // the library's workers for one image
};

class LibraryDetector {
 public:
  // `family`: a family the library has tables for (vision/tag_family.h).
  static StatusOr<std::unique_ptr<LibraryDetector>> Create(const std::string& family,
                                                           const LibraryDetectorSettings& settings = {});
  ~LibraryDetector();
  LibraryDetector(const LibraryDetector&) = delete;
  LibraryDetector& operator=(const LibraryDetector&) = delete;

  // Every tag the library decodes in `gray` (CV_8UC1), corners shifted by
  // −½ px to OpenCV's pixel-centre convention, in the library's order.
  std::vector<DecodedTag> Detect(const cv::Mat& gray);

 private:
  struct Impl;
  explicit LibraryDetector(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hexcal

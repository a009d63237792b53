// Image files as the 8-bit grey image that detection reads.
//
// One documented way for every file (docs/vision.md, "Image files"):
// - PNG, JPEG and TIFF only; the header is checked before decoding
//   (vision/image_header.h): truncated files and files over kMaxImagePixels
//   are refused with the reason, never decoded.
// - Pixels as stored. EXIF / TIFF orientation is never applied: a camera's
//   intrinsics are in the sensor's pixel grid, and a phone that rotates its
//   photos in the viewer would otherwise move the principal point between
//   portrait and landscape shots. The orientation is reported (ImageNotes).
// - Colour is converted to grey (0.299 R + 0.587 G + 0.114 B); an alpha
//   channel is composited over white, as the sheet it was printed on.
// - 16-bit and floating-point images are scaled by their range: the darkest
//   pixel becomes 0 and the brightest 255. A 12-bit sensor stored in 16 bits
//   (0-4095) is not crushed into 0-15, as taking the high byte would do.
//
//   ImageNotes notes;
//   StatusOr<cv::Mat> gray = LoadGrayImage("view.png", &notes);
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"

namespace hexcal {

// What the file held before it became 8-bit grey.
struct ImageNotes {
  int bits = 8;          // per channel: 8, 16, 32 (float)
  int channels = 1;      // 1 grey, 2 grey + alpha, 3 colour, 4 colour + alpha
  int orientation = 1;   // EXIF / TIFF Orientation 1-8, not applied
  double range_low = 0;  // the grey values mapped to 0 and 255 (bits > 8)
  double range_high = 255;
};

// An image file as 8-bit grey (CV_8UC1). Errors name the file: missing, empty,
// truncated, over kMaxImagePixels by its header, or not a readable PNG / JPEG /
// TIFF ("cannot decode: ...").
StatusOr<cv::Mat> LoadGrayImage(const std::string& path, ImageNotes* notes = nullptr);
// The same for the file's bytes already in memory; `source` names it in messages.
StatusOr<cv::Mat> DecodeGrayImage(const std::string& bytes, const std::string& source, ImageNotes* notes = nullptr);

// A note for a person when the file needed more than reading as stored
// ("16-bit, grey 812-60211 scaled to 0-255; EXIF orientation 6 not applied"),
// or "".
std::string DescribeImageNotes(const ImageNotes& notes);

}  // namespace hexcal

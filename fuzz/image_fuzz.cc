// libFuzzer target: image loading (vision/detection.h DecodeGrayImage, the
// body of LoadGrayImage that `hexcal measure` and the session calibration use).
// The decoders themselves are OpenCV's and not instrumented, so this finds
// crashes and leaks on the way through them, not new coverage inside them.
// docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "vision/detection.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<cv::Mat> image = hexcal::DecodeGrayImage(bytes, "fuzz.png");
  if (image.ok() && (image->empty() || image->type() != CV_8UC1)) std::abort();
  return 0;
}

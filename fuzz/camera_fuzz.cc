// libFuzzer target: camera files (vision/camera.h), OpenCV FileStorage, ROS
// camera_info and Kalibr camchain YAML; a camera the parser accepts is written
// in every format that holds it and must parse again to the same camera.
// docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "vision/camera.h"

namespace {

bool SameCamera(const hexcal::Camera& a, const hexcal::Camera& b) {
  return a.model == b.model && a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy && a.distortion == b.distortion;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::Camera> camera = hexcal::ParseCameraFile(text, "fuzz.yaml");
  if (!camera.ok()) return 0;
  for (hexcal::CameraFileFormat format :
       {hexcal::CameraFileFormat::kOpenCv, hexcal::CameraFileFormat::kRos, hexcal::CameraFileFormat::kKalibr}) {
    const hexcal::StatusOr<std::string> written = hexcal::CameraToText(*camera, format);
    if (!written.ok()) {
      if (format != hexcal::CameraFileFormat::kKalibr) std::abort();  // only Kalibr may refuse a valid camera
      continue;
    }
    const hexcal::StatusOr<hexcal::Camera> back = hexcal::ParseCameraFile(*written, "round-trip.yaml");
    if (!back.ok() || !SameCamera(*back, *camera)) std::abort();
  }
  return 0;
}

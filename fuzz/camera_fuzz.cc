// libFuzzer target: camera files (vision/camera.h), OpenCV FileStorage and ROS
// camera_info YAML; a camera the parser accepts is written back and must parse
// again. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "vision/camera.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::Camera> camera = hexcal::ParseCameraFile(text, "fuzz.yaml");
  if (!camera.ok()) return 0;
  if (!hexcal::ParseCameraFile(hexcal::CameraToOpenCvYaml(*camera), "round-trip.yaml").ok()) std::abort();
  return 0;
}

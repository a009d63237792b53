// A GigE Vision camera inside this process that serves the images a function
// renders: libaravis' own simulator (ArvGvFakeCamera) with its fill pattern
// replaced by a copy of the rendered image, so every frame arrives
// byte-identical. Tests and demos open it like a real camera, through
// OpenFrameSource("aravis:" + DeviceId()) and the network stack.
//
//   StatusOr<std::unique_ptr<FakeGenICamCamera>> fake =
//       FakeGenICamCamera::Start({}, [&] { return world.RenderFrame(); });
//   if (!fake.ok()) return fake.status();
//   StatusOr<std::unique_ptr<FrameSource>> camera = OpenFrameSource("aravis:" + (*fake)->DeviceId());
//
// What it serves (Aravis 0.8.26's simulator):
// - 25 frames per second, free running: the simulator's default
//   (ARV_FAKE_CAMERA_ACQUISITION_FRAME_RATE_DEFAULT), on multiples of 40 ms of
//   the wall clock; a client may change it through AcquisitionFrameRate
//   (0.1-1000). The aravis: camera does not.
// - Mono8 at the rendered size (SensorWidth/Width and SensorHeight/Height are
//   set to it); `render` is called once per frame, at the frame's start, on
//   Aravis' thread (and once by Start, on the caller's, when the size comes
//   from the first frame), and must return CV_8UC1 of that size: anything
//   else is served as a black frame.
// - ExposureTimeAbs (10-1e7 µs) and GainRaw (0-10) are registers only: they
//   do not change the image.
// - One camera per address (the GVCP port, UDP 3956): a second Start on the
//   same address is refused (kBusy). CTest runs the tests that start one
//   under RESOURCE_LOCK "genicam_loopback".
//
// Built only where Aravis is found (HEXCAL_HAVE_ARAVIS).
#pragma once

#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"

namespace hexcal::workflow {

struct FakeCameraOptions {
  std::string interface = "127.0.0.1";  // the network interface it serves on, by IPv4 address or name
  std::string serial = "HEXCAL01";      // 1-15 characters; the device id is "Aravis-Fake-" + serial
  int width = 0, height = 0;            // pixels; 0: the size of the first rendered frame
  double lost_packet_ratio = 0;         // [0, 1]: stream packets left unsent, for tests of incomplete frames
};

class FakeGenICamCamera {
 public:
  // `render` is called from Aravis' streaming thread for each frame and returns a CV_8UC1 image of width x height.
  static StatusOr<std::unique_ptr<FakeGenICamCamera>> Start(const FakeCameraOptions& options,
                                                            std::function<cv::Mat()> render);
  ~FakeGenICamCamera();  // stops serving (joins Aravis' thread: `render` is not called after it)
  FakeGenICamCamera(const FakeGenICamCamera&) = delete;
  FakeGenICamCamera& operator=(const FakeGenICamCamera&) = delete;

  std::string DeviceId() const;  // what `aravis:` takes to open this camera

 private:
  struct Impl;
  explicit FakeGenICamCamera(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hexcal::workflow

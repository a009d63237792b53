// Cameras for the Acquire step (docs/acquisition.md): one interface, opened
// from a URL (OpenFrameSource, device_urls.h), so that the CLI (`hexcal
// acquire --camera URL`) and the GUI's Acquire step take frames the same way.
//
//   sim            the sim world's camera (sim/sim_world.h): the board
//                  rendered at the simulated platform's true pose
//   v4l2:N         /dev/videoN through OpenCV's V4L2 backend
//   file:PATH      a video file (one frame per Grab, in order) or an image
//                  (the same frame every time), through OpenCV
//   aravis:NAME[?exposure=US&gain=DB]
//                  a GenICam camera (GigE Vision, USB3 Vision) through Aravis,
//                  NAME as arv-tool-0.8 lists it; each Grab gives a frame that
//                  started after the call (devices/aravis_frame_source.h).
//                  A build without Aravis refuses it, naming the package.
//
//   StatusOr<std::unique_ptr<FrameSource>> camera = OpenFrameSource("v4l2:0");
//   if (!camera.ok()) return camera.status();  // names the URL and the forms above
//   StatusOr<cv::Mat> frame = (*camera)->Grab(std::chrono::seconds(2));
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"

namespace hexcal::workflow {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame (CV_8UC1 or CV_8UC3). Errors name the source: a time-out,
  // an empty or dropped frame, the end of a video (kind kFailed), a device
  // that went away (kIo).
  virtual StatusOr<cv::Mat> Grab(std::chrono::milliseconds timeout) = 0;
  // "sim camera (sim-4.2mm-1024x768)", "v4l2:0 (640x480)", "file:run.mp4": for logs.
  virtual std::string Describe() const = 0;
  // Exposure time in microseconds and analogue gain in dB; a source that
  // cannot set them returns a bad-input status saying so.
  virtual Status SetExposure(double microseconds);
  virtual Status SetGain(double decibels);
};

struct FrameSourceOptions {
  // Opens the `sim` camera, which looks at the world the `sim` controller
  // moves: set by SimFrameSourceOptions (sim/sim_world.h; OpenAcquisitionRig
  // in workflow/acquire_step.h makes them together).
  std::function<std::unique_ptr<FrameSource>()> sim;
};

// The accepted URL forms, for messages and --help.
constexpr const char* kFrameSourceForms = "sim, v4l2:N, file:PATH, aravis:NAME[?exposure=US&gain=DB]";

// The refusal of a camera URL: bad input naming the URL, the problem and the forms.
Status BadFrameSourceUrl(const std::string& url, const std::string& problem);
// file:PATH (`path` after the colon) and v4l2:N (`device`); OpenFrameSource
// (device_urls.h) opens every kind by URL.
StatusOr<std::unique_ptr<FrameSource>> OpenFileFrameSource(const std::string& url, const std::string& path);
StatusOr<std::unique_ptr<FrameSource>> OpenV4l2FrameSource(const std::string& url, const std::string& device);

}  // namespace hexcal::workflow

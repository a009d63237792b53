// A video file or camera opened through OpenCV's videoio, as hexcal uses it:
// the interface between the module hexcal_opencv_io, whose streams implement
// it (opencv_io_plugin.cc), and the callers of OpenVideoFile and
// OpenVideoDevice (image_codecs.h). Apart from image_codecs.h so that the
// module's table (opencv_io_plugin.h) need not include the loader's header.
//
//   StatusOr<std::unique_ptr<VideoStream>> video = OpenVideoFile("sweep.mp4");
//   cv::Mat frame;
//   while (video.ok() && (*video)->Read(&frame)) Detect(frame);
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace hexcal {

// The part of cv::VideoCapture hexcal uses; properties are cv::CAP_PROP_*.
class VideoStream {
 public:
  virtual ~VideoStream() = default;
  virtual bool Read(cv::Mat* frame) = 0;
  virtual double Get(int property) const = 0;
  virtual bool Set(int property, double value) = 0;
  virtual std::string BackendName() const = 0;
};

}  // namespace hexcal

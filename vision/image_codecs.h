// Image files and video through OpenCV's imgcodecs and videoio, loaded on the
// first call rather than at start-up. The two libraries bring about 200 shared
// libraries with them (GDAL, FFmpeg, GStreamer), whose loading and symbol
// binding took 0.19 s of every hexcal process's 0.21 s start, whether it read
// an image or not (docs/performance.md, "Process start"). They live in the
// module hexcal_opencv_io, found next to the build's libraries, beside the
// executable, or at $HEXCAL_OPENCV_IO (docs/architecture.md).
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "core/status.h"
#include "vision/video_stream.h"

namespace hexcal {

// The image as stored (cv::IMREAD_UNCHANGED: every channel and bit, orientation
// not applied); an error when OpenCV cannot decode it or cannot be loaded.
StatusOr<cv::Mat> DecodeImage(const std::string& bytes);
StatusOr<cv::Mat> ReadImageFile(const std::string& path);
StatusOr<std::string> EncodePng(const cv::Mat& image);

// A video file or device as the stream of video_stream.h.
StatusOr<std::unique_ptr<VideoStream>> OpenVideoFile(const std::string& path);
// `api`: a cv::VideoCaptureAPIs value, e.g. cv::CAP_V4L2.
StatusOr<std::unique_ptr<VideoStream>> OpenVideoDevice(int index, int api);

// Passes LibraryLogsShown() (library_logs.h) to the module's libraries when the
// module is loaded; it is passed again whenever the module loads.
void ApplyLibraryLogsToCodecs();

}  // namespace hexcal

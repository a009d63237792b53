// The table of OpenCV imgcodecs and videoio calls that hexcal makes, shared by
// the plugin that makes them (opencv_io_plugin.cc, the module
// hexcal_opencv_io) and its loader (image_codecs.cc). Callers use
// image_codecs.h; only those two files include this header.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "vision/video_stream.h"

namespace hexcal {

// Each call returns "" on success or why it failed (OpenCV's message).
struct OpenCvIoPlugin {
  int version;  // kOpenCvIoPluginVersion of the plugin's build
  std::string (*decode)(const std::string& bytes, int flags, cv::Mat* image);
  std::string (*encode)(const std::string& extension, const cv::Mat& image, std::string* bytes);
  // nullptr and `error` set when the file or device cannot be opened.
  VideoStream* (*open_video_file)(const std::string& path, std::string* error);
  VideoStream* (*open_video_device)(int index, int api, std::string* error);
  // FFmpeg's and GLib's log lines on stderr or dropped (library_logs.h).
  void (*show_library_logs)(bool shown);
};

constexpr int kOpenCvIoPluginVersion = 3;

}  // namespace hexcal

// The plugin's one exported symbol.
extern "C" const hexcal::OpenCvIoPlugin* hexcal_opencv_io_plugin();

#include "vision/library_logs.h"

#include <atomic>
#include <opencv2/core/utils/logger.hpp>

#include "vision/image_codecs.h"

namespace hexcal {
namespace {

std::atomic<bool> shown{false};

}  // namespace

void ShowLibraryLogs(bool show) {
  shown = show;
  cv::utils::logging::setLogLevel(show ? cv::utils::logging::LOG_LEVEL_INFO : cv::utils::logging::LOG_LEVEL_SILENT);
  // FFmpeg's and GLib's, through the module that loads them (when it is loaded
  // already; else when it is, image_codecs.cc).
  ApplyLibraryLogsToCodecs();
}

bool LibraryLogsShown() { return shown; }

}  // namespace hexcal

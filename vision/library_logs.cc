#include "vision/library_logs.h"

#include <atomic>
#include <opencv2/core/utils/logger.hpp>


namespace hexcal {
namespace {

std::atomic<bool> shown{false};
std::atomic<void (*)()> listener{nullptr};

}  // namespace

void ShowLibraryLogs(bool show) {
  shown = show;
  cv::utils::logging::setLogLevel(show ? cv::utils::logging::LOG_LEVEL_INFO : cv::utils::logging::LOG_LEVEL_SILENT);
  // FFmpeg's and GLib's, through the module that loads them (when it is loaded
  // already; else when it is, image_codecs.cc).
  if (void (*apply)() = listener) apply();
}

void SetLibraryLogsListener(void (*apply)()) { listener = apply; }

bool LibraryLogsShown() { return shown; }

}  // namespace hexcal

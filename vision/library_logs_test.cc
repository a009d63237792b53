// GLib's lines (GStreamer's and Aravis' warnings, docs/hardening.md) reach
// stderr only with `hexcal --verbose`: both of GLib's routes, the classic
// g_log and the structured g_log_structured, once the image module that sets
// the handlers (vision/image_codecs.h) is loaded.
#include "vision/library_logs.h"

#include <glib.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "vision/image_codecs.h"

namespace hexcal {
namespace {

// What a GLib warning of each route leaves on stderr.
std::string StderrOfGlibWarnings(const char* marker) {
  testing::internal::CaptureStderr();
  g_log("GStreamer", G_LOG_LEVEL_WARNING, "classic %s", marker);
  g_log_structured("Aravis", G_LOG_LEVEL_WARNING, "MESSAGE", "structured %s", marker);
  return testing::internal::GetCapturedStderr();
}

TEST(LibraryLogs, GlibWarningsOnlyWhenShown) {
  ASSERT_TRUE(EncodePng(cv::Mat(4, 4, CV_8UC1, cv::Scalar(7))).ok());  // loads the image module
  ShowLibraryLogs(false);
  EXPECT_EQ(StderrOfGlibWarnings("quiet"), "");
  ShowLibraryLogs(true);
  const std::string loud = StderrOfGlibWarnings("loud");
  EXPECT_NE(loud.find("classic loud"), std::string::npos) << loud;
  EXPECT_NE(loud.find("structured loud"), std::string::npos) << loud;
  ShowLibraryLogs(false);
  EXPECT_EQ(StderrOfGlibWarnings("quiet again"), "");
}

}  // namespace
}  // namespace hexcal

// The module hexcal_opencv_io: the only code that links OpenCV's imgcodecs and
// videoio (image_codecs.h says why). Every OpenCV exception stays in here.
#include "vision/opencv_io_plugin.h"

#include <atomic>
#include <cstdarg>
#include <exception>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#ifdef HEXCAL_HAVE_AVUTIL
extern "C" {
#include <libavutil/log.h>
}
#endif
#ifdef HEXCAL_HAVE_GLIB
#include <glib.h>
#endif

namespace hexcal {
namespace {

// Runs `call`; "" when it returns normally, else what it threw.
template <typename Call>
std::string Catching(Call call) {
  try {
    call();
    return "";
  } catch (const cv::Exception& e) {
    return e.msg;
  } catch (const std::exception& e) {  // e.g. std::bad_alloc for a header claiming a huge image
    return e.what();
  }
}

class CaptureStream final : public VideoStream {
 public:
  explicit CaptureStream(std::unique_ptr<cv::VideoCapture> capture) : capture_(std::move(capture)) {}
  bool Read(cv::Mat* frame) override { return capture_->read(*frame); }
  double Get(int property) const override { return capture_->get(property); }
  bool Set(int property, double value) override { return capture_->set(property, value); }
  std::string BackendName() const override { return capture_->getBackendName(); }

 private:
  std::unique_ptr<cv::VideoCapture> capture_;
};

// The stream `make` opens, or nullptr with why not.
template <typename Make>
VideoStream* OpenWith(Make make, std::string* error) {
  std::unique_ptr<cv::VideoCapture> capture;
  const std::string thrown = Catching([&] { capture = make(); });
  if (!thrown.empty() || !capture->isOpened()) {
    *error = thrown.empty() ? "cannot be opened" : thrown;
    return nullptr;
  }
  return new CaptureStream(std::move(capture));
}

std::string Decode(const std::string& bytes, int flags, cv::Mat* image) {
  // imdecode only reads the buffer; the const_cast is what cv::Mat's constructor needs.
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
  return Catching([&] { *image = cv::imdecode(buffer, flags); });
}

std::string Encode(const std::string& extension, const cv::Mat& image, std::string* bytes) {
  std::vector<uchar> encoded;
  bool done = false;
  std::string error = Catching([&] { done = cv::imencode(extension, image, encoded); });
  if (error.empty() && !done) return "OpenCV cannot encode it as " + extension;
  bytes->assign(encoded.begin(), encoded.end());
  return error;
}

// Through FFmpeg, then GStreamer. Not every backend: when a file opens with
// neither, OpenCV would go on to probe for cameras (its gPhoto2 backend
// enumerates the USB bus), which is slow and never a file's reader.
VideoStream* OpenFile(const std::string& path, std::string* error) {
  VideoStream* stream = OpenWith([&] { return std::make_unique<cv::VideoCapture>(path, cv::CAP_FFMPEG); }, error);
  if (!stream) stream = OpenWith([&] { return std::make_unique<cv::VideoCapture>(path, cv::CAP_GSTREAMER); }, error);
  return stream;
}

VideoStream* OpenDevice(int index, int api, std::string* error) {
  return OpenWith([&] { return std::make_unique<cv::VideoCapture>(index, api); }, error);
}

#ifdef HEXCAL_HAVE_AVUTIL
void DropFfmpegLine(void*, int, const char*, va_list) {}
#endif
#ifdef HEXCAL_HAVE_GLIB
// GLib's errors abort the process whatever the handler; say why first.
void DropGlibLine(const gchar* domain, GLogLevelFlags level, const gchar* message, gpointer data) {
  if ((level & G_LOG_LEVEL_ERROR) != 0) g_log_default_handler(domain, level, message, data);
}

std::atomic<bool> glib_lines_shown{true};

// Structured messages (g_log_structured, and g_warning in code built with
// G_LOG_USE_STRUCTURED) bypass the default handler and reach the writer.
GLogWriterOutput WriteGlibLine(GLogLevelFlags level, const GLogField* fields, gsize n_fields, gpointer data) {
  if (glib_lines_shown || (level & G_LOG_LEVEL_ERROR) != 0) return g_log_writer_default(level, fields, n_fields, data);
  return G_LOG_WRITER_HANDLED;
}

// GLib allows one writer per process, set by the program: hexcal sets it
// once, and it then follows glib_lines_shown.
void ShowGlibLines(bool shown) {
  glib_lines_shown = shown;
  static std::once_flag writer_set;
  std::call_once(writer_set, [] { g_log_set_writer_func(WriteGlibLine, nullptr, nullptr); });
  g_log_set_default_handler(shown ? g_log_default_handler : DropGlibLine, nullptr);
}
#endif

// FFmpeg's lines ("[mov,mp4,m4a,3gp,3g2,mj2 @ 0x...] moov atom not found" for
// a corrupt video) and GLib's (GStreamer's warnings) on stderr or dropped.
void ShowLibraryLogs(bool shown) {
#ifdef HEXCAL_HAVE_AVUTIL
  av_log_set_callback(shown ? av_log_default_callback : DropFfmpegLine);
#endif
#ifdef HEXCAL_HAVE_GLIB
  ShowGlibLines(shown);
#endif
  (void)shown;
}

}  // namespace
}  // namespace hexcal

extern "C" __attribute__((visibility("default"))) const hexcal::OpenCvIoPlugin* hexcal_opencv_io_plugin() {
  static const hexcal::OpenCvIoPlugin plugin = {
      hexcal::kOpenCvIoPluginVersion, hexcal::Decode, hexcal::Encode, hexcal::OpenFile, hexcal::OpenDevice,
      hexcal::ShowLibraryLogs};
  return &plugin;
}

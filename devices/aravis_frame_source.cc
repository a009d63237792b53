#include "devices/aravis_frame_source.h"

#include <arv.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "devices/glib_handles.h"
#include "vision/library_logs.h"

namespace hexcal::workflow {
namespace {

constexpr int kStreamBuffers = 4;
constexpr int kSocketBufferBytes = 4 << 20;  // fixed: every frame arrives on loopback (devices.md)
constexpr gint64 kUnknownFramePeriodUs = 100000;

std::string Number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Aravis' own lines on stderr ("[12:00:01.234] 🅸 policies> ..." by default)
// only with hexcal --verbose (vision/library_logs.h): then its warnings, or
// what $ARV_DEBUG asks for; else none, whatever $ARV_DEBUG says.
void ApplyLibraryLogsToAravis() {
  const char* asked = std::getenv("ARV_DEBUG");
  arv_debug_enable(!LibraryLogsShown() ? "all:0" : asked != nullptr && *asked != '\0' ? asked : "all:1");
}

std::string CamerasSeen() {
  const std::vector<std::string> cameras = ListAravisCameras();
  if (cameras.empty()) return "Aravis sees no camera";
  std::string list = "Aravis sees: ";
  for (size_t k = 0; k < cameras.size(); ++k) list += (k > 0 ? ", " : "") + cameras[k];
  return list;
}

// OpenCV's conversion of a camera pixel format to CV_8UC1/CV_8UC3, or -1 to
// copy Mono8 as it is; nullopt: not a format hexcal reads.
std::optional<int> Conversion(ArvPixelFormat format) {
  if (format == ARV_PIXEL_FORMAT_MONO_8 || format == ARV_PIXEL_FORMAT_BGR_8_PACKED) return -1;
  if (format == ARV_PIXEL_FORMAT_RGB_8_PACKED) return cv::COLOR_RGB2BGR;
  // GenICam names a Bayer pattern by its first two pixels, as these OpenCV aliases do.
  if (format == ARV_PIXEL_FORMAT_BAYER_RG_8) return cv::COLOR_BayerRGGB2GRAY;
  if (format == ARV_PIXEL_FORMAT_BAYER_GR_8) return cv::COLOR_BayerGRBG2GRAY;
  if (format == ARV_PIXEL_FORMAT_BAYER_GB_8) return cv::COLOR_BayerGBRG2GRAY;
  if (format == ARV_PIXEL_FORMAT_BAYER_BG_8) return cv::COLOR_BayerBGGR2GRAY;
  return std::nullopt;
}

// Gives a popped buffer back to the stream's input queue on every path.
class Requeue {
 public:
  Requeue(ArvStream* stream, ArvBuffer* buffer) : stream_(stream), buffer_(buffer) {}
  Requeue(const Requeue&) = delete;
  Requeue& operator=(const Requeue&) = delete;
  ~Requeue() { arv_stream_push_buffer(stream_, buffer_); }

 private:
  ArvStream* stream_;
  ArvBuffer* buffer_;
};

// Mono8 where the camera has it; otherwise its format must be one ToImage reads.
Status SelectPixelFormat(ArvCamera* camera, const std::string& url) {
  GErrorHolder error;
  guint count = 0;
  gint64* formats = arv_camera_dup_available_pixel_formats(camera, &count, error.out());
  const bool has_mono8 = formats != nullptr && std::count(formats, formats + count, ARV_PIXEL_FORMAT_MONO_8) > 0;
  g_free(formats);
  if (has_mono8) {
    arv_camera_set_pixel_format(camera, ARV_PIXEL_FORMAT_MONO_8, error.out());
    if (error.failed()) return Status::IoError(url + ": setting the pixel format to Mono8 failed: " + error.message());
    return Status::Ok();
  }
  if (Conversion(arv_camera_get_pixel_format(camera, error.out()))) return Status::Ok();
  const char* name = arv_camera_get_pixel_format_as_string(camera, error.out());
  return Status::BadInput(url + ": the camera has no Mono8, and hexcal does not read its pixel format " +
                          (name != nullptr ? name : "?") + " (Mono8, RGB8, BGR8 and 8-bit Bayer are read)");
}

StatusOr<GObjectPtr<ArvStream>> StartStream(ArvCamera* camera, const std::string& url) {
  GErrorHolder error;
  if (arv_camera_is_gv_device(camera))
    arv_camera_gv_set_stream_options(camera, ARV_GV_STREAM_OPTION_PACKET_SOCKET_DISABLED);
  GObjectPtr<ArvStream> stream(arv_camera_create_stream(camera, nullptr, nullptr, error.out()));
  if (!stream) return Status::IoError(url + ": cannot open the camera's stream: " + error.message());
  if (ARV_IS_GV_STREAM(stream.get()))
    g_object_set(stream.get(), "socket-buffer", ARV_GV_STREAM_SOCKET_BUFFER_FIXED, "socket-buffer-size",
                 kSocketBufferBytes, nullptr);
  const guint payload = arv_camera_get_payload(camera, error.out());
  if (error.failed() || payload == 0) return Status::IoError(url + ": the camera gives no payload size");
  for (int k = 0; k < kStreamBuffers; ++k) arv_stream_push_buffer(stream.get(), arv_buffer_new(payload, nullptr));
  arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, error.out());
  if (!error.failed()) arv_camera_start_acquisition(camera, error.out());
  if (error.failed()) return Status::IoError(url + ": cannot start the acquisition: " + error.message());
  return stream;
}

class AravisFrameSource final : public FrameSource {
 public:
  AravisFrameSource(std::string url, GObjectPtr<ArvCamera> camera, std::string description)
      : url_(std::move(url)), camera_(std::move(camera)), description_(std::move(description)) {
    UpdateSettleTime();
  }

  ~AravisFrameSource() override {
    if (!stream_) return;
    GErrorHolder ignored;
    arv_camera_stop_acquisition(camera_.get(), ignored.out());
    stream_.reset();  // joins the stream thread before the device goes
  }

  // Free-running acquisition into kStreamBuffers buffers; once, after the
  // settings of the URL.
  Status Start() {
    StatusOr<GObjectPtr<ArvStream>> stream = StartStream(camera_.get(), url_);
    if (!stream.ok()) return stream.status();
    stream_ = std::move(*stream);
    return Status::Ok();
  }

  // A frame that started after this call. Aravis stamps a GigE Vision or USB3
  // buffer's system timestamp with the host's real-time clock when the
  // frame's leader arrives (arvgvstream.c, arvuvstream.c: g_get_real_time).
  // The leader leaves the camera after the exposure ends, and for a camera
  // that keeps up with its own frame rate less than one frame period later,
  // so a frame is taken only if it arrived at least exposure + one period
  // after the request (settle_us_). That costs up to one extra period per
  // grab; it relies on the host clock not being stepped during the grab.
  StatusOr<cv::Mat> Grab(std::chrono::milliseconds timeout) override {
    const gint64 request_us = g_get_real_time();
    const gint64 deadline_us = g_get_monotonic_time() + std::max<gint64>(0, timeout.count()) * 1000;
    int incomplete = 0, early = 0;
    DropWaitingBuffers();
    for (gint64 left_us = deadline_us - g_get_monotonic_time(); left_us > 0;
         left_us = deadline_us - g_get_monotonic_time()) {
      ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_.get(), static_cast<guint64>(left_us));
      if (buffer == nullptr) break;
      Requeue requeue(stream_.get(), buffer);
      if (!first_frame_dropped_) {
        first_frame_dropped_ = true;  // often "missing packets" (devices.md)
        continue;
      }
      if (arv_buffer_get_status(buffer) != ARV_BUFFER_STATUS_SUCCESS) {
        ++incomplete;
        continue;
      }
      if (static_cast<gint64>(arv_buffer_get_system_timestamp(buffer) / 1000) < request_us + settle_us_) {
        ++early;
        continue;
      }
      return ToImage(buffer);
    }
    return Status::Failed(url_ + ": no complete frame started after the request within " +
                          std::to_string(timeout.count()) + " ms (" + std::to_string(incomplete) +
                          " incomplete frames: missing packets or late; " + std::to_string(early) +
                          " complete frames that may have started before the request)");
  }

  std::string Describe() const override { return description_; }

  Status SetExposure(double microseconds) override {
    if (!std::isfinite(microseconds) || microseconds <= 0)
      return Status::BadInput(url_ + ": exposure must be a positive number of microseconds, not " +
                              Number(microseconds));
    GErrorHolder error;
    if (!arv_camera_is_exposure_time_available(camera_.get(), error.out()))
      return FrameSource::SetExposure(microseconds);
    double min = 0, max = 0;
    arv_camera_get_exposure_time_bounds(camera_.get(), &min, &max, error.out());
    if (!error.failed() && (microseconds < min || microseconds > max))
      return Status::BadInput(url_ + ": exposure " + Number(microseconds) + " µs is outside the camera's range [" +
                              Number(min) + ", " + Number(max) + "] µs");
    arv_camera_set_exposure_time(camera_.get(), microseconds, error.out());
    if (error.failed()) return Status::IoError(url_ + ": setting the exposure failed: " + error.message());
    UpdateSettleTime();
    return Status::Ok();
  }

  Status SetGain(double decibels) override {
    if (!std::isfinite(decibels))
      return Status::BadInput(url_ + ": gain must be a number of dB, not " + Number(decibels));
    GErrorHolder error;
    if (!arv_camera_is_gain_available(camera_.get(), error.out())) return FrameSource::SetGain(decibels);
    double min = 0, max = 0;
    arv_camera_get_gain_bounds(camera_.get(), &min, &max, error.out());
    if (!error.failed() && (decibels < min || decibels > max))
      return Status::BadInput(url_ + ": gain " + Number(decibels) + " is outside the camera's range [" + Number(min) +
                              ", " + Number(max) + "]");
    arv_camera_set_gain(camera_.get(), decibels, error.out());
    if (error.failed()) return Status::IoError(url_ + ": setting the gain failed: " + error.message());
    return Status::Ok();
  }

 private:
  void DropWaitingBuffers() {
    for (int k = 0; k < 2 * kStreamBuffers; ++k) {
      ArvBuffer* buffer = arv_stream_try_pop_buffer(stream_.get());
      if (buffer == nullptr) return;
      first_frame_dropped_ = true;
      arv_stream_push_buffer(stream_.get(), buffer);
    }
  }

  void UpdateSettleTime() {
    GErrorHolder error;
    double exposure_us = 0;
    if (arv_camera_is_exposure_time_available(camera_.get(), error.out()))
      exposure_us = arv_camera_get_exposure_time(camera_.get(), error.out());
    gint64 period_us = kUnknownFramePeriodUs;
    if (arv_camera_is_frame_rate_available(camera_.get(), error.out())) {
      const double rate = arv_camera_get_frame_rate(camera_.get(), error.out());
      if (!error.failed() && rate > 0) period_us = static_cast<gint64>(1e6 / rate);
    }
    settle_us_ = static_cast<gint64>(std::max(0.0, exposure_us)) + period_us;
  }

  StatusOr<cv::Mat> ToImage(ArvBuffer* buffer) const {
    const ArvPixelFormat format = arv_buffer_get_image_pixel_format(buffer);
    const int width = arv_buffer_get_image_width(buffer), height = arv_buffer_get_image_height(buffer);
    const int channels = format == ARV_PIXEL_FORMAT_RGB_8_PACKED || format == ARV_PIXEL_FORMAT_BGR_8_PACKED ? 3 : 1;
    size_t size = 0;
    const void* data = arv_buffer_get_image_data(buffer, &size);
    const std::optional<int> conversion = Conversion(format);
    if (!conversion) return Status::Failed(url_ + ": frames in pixel format " + Number(format) + " are not read");
    if (data == nullptr || width <= 0 || height <= 0 || size < static_cast<size_t>(width) * height * channels)
      return Status::Failed(url_ + ": a " + std::to_string(width) + "x" + std::to_string(height) + " frame of " +
                            std::to_string(size) + " bytes");
    const cv::Mat view(height, width, CV_8UC(channels), const_cast<void*>(data));
    cv::Mat image;
    if (*conversion < 0)
      image = view.clone();
    else
      cv::cvtColor(view, image, *conversion);
    return image;
  }

  std::string url_;
  GObjectPtr<ArvCamera> camera_;
  GObjectPtr<ArvStream> stream_;
  std::string description_;
  bool first_frame_dropped_ = false;
  gint64 settle_us_ = 0;  // exposure + one frame period (Grab)
};

std::string DescribeCamera(ArvCamera* camera, const std::string& url) {
  GErrorHolder error;
  const auto text = [](const char* value) { return std::string(value != nullptr ? value : "?"); };
  const std::string vendor = text(arv_camera_get_vendor_name(camera, error.out()));
  const std::string model = text(arv_camera_get_model_name(camera, error.out()));
  const std::string serial = text(arv_camera_get_device_serial_number(camera, error.out()));
  gint x = 0, y = 0, width = 0, height = 0;
  arv_camera_get_region(camera, &x, &y, &width, &height, error.out());
  const std::string format = text(arv_camera_get_pixel_format_as_string(camera, error.out()));
  return url + " (" + vendor + " " + model + " " + serial + ", " + std::to_string(width) + "x" +
         std::to_string(height) + " " + format + ")";
}

}  // namespace

std::vector<std::string> ListAravisCameras() {
  ApplyLibraryLogsToAravis();
  arv_update_device_list();
  std::vector<std::string> cameras;
  for (unsigned k = 0; k < arv_get_n_devices(); ++k) {
    const char* id = arv_get_device_id(k);
    const char* address = arv_get_device_address(k);
    cameras.push_back(std::string(id != nullptr ? id : "?") +
                      (address != nullptr && *address != '\0' ? " (" + std::string(address) + ")" : ""));
  }
  return cameras;
}

StatusOr<std::unique_ptr<FrameSource>> OpenAravisFrameSource(const std::string& url) {
  StatusOr<AravisUrl> parsed = ParseAravisUrl(url);
  if (!parsed.ok()) return parsed.status();
  ApplyLibraryLogsToAravis();
  GErrorHolder error;
  GObjectPtr<ArvCamera> camera(arv_camera_new(parsed->device_id.c_str(), error.out()));
  if (!camera) {
    const std::string why = error.message();
    if (g_error_matches(error.get(), ARV_DEVICE_ERROR, ARV_DEVICE_ERROR_NOT_FOUND))
      return Status::BadInput("camera '" + url + "': no GenICam camera '" + parsed->device_id + "'; " + CamerasSeen());
    return Status::IoError("camera '" + url + "': cannot open it: " + why + "; " + CamerasSeen());
  }
  if (Status format = SelectPixelFormat(camera.get(), url); !format.ok()) return format;
  const std::string description = DescribeCamera(camera.get(), url);
  auto source = std::make_unique<AravisFrameSource>(url, std::move(camera), description);
  if (parsed->exposure_us)
    if (Status set = source->SetExposure(*parsed->exposure_us); !set.ok()) return set;
  if (parsed->gain_db)
    if (Status set = source->SetGain(*parsed->gain_db); !set.ok()) return set;
  if (Status started = source->Start(); !started.ok()) return started;
  return std::unique_ptr<FrameSource>(std::move(source));
}

}  // namespace hexcal::workflow

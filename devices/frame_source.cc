#include "devices/frame_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>
#include <opencv2/videoio.hpp>

#include "core/atomic_file.h"
#include "vision/image_codecs.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// An image file: the same frame at every Grab (a still scene, or a test).
class StillImageSource final : public FrameSource {
 public:
  StillImageSource(std::string url, cv::Mat image) : url_(std::move(url)), image_(std::move(image)) {}
  StatusOr<cv::Mat> Grab(std::chrono::milliseconds) override { return image_.clone(); }
  std::string Describe() const override {
    return url_ + " (still image " + std::to_string(image_.cols) + "x" + std::to_string(image_.rows) + ")";
  }

 private:
  std::string url_;
  cv::Mat image_;
};

// A device or a video file through cv::VideoCapture. OpenCV's read blocks
// (V4L2 gives up after its own select() time-out of 10 s), so a frame that
// comes later than `timeout` is refused after the fact: the caller learns the
// camera is too slow, rather than getting a frame from the wrong moment.
class CaptureSource final : public FrameSource {
 public:
  CaptureSource(std::string url, std::unique_ptr<VideoStream> capture, bool is_device)
      : url_(std::move(url)), capture_(std::move(capture)), is_device_(is_device) {}

  StatusOr<cv::Mat> Grab(std::chrono::milliseconds timeout) override {
    const auto start = std::chrono::steady_clock::now();
    cv::Mat frame;
    const bool read = capture_->Read(&frame);
    const double waited_ms = MillisecondsSince(start);
    if (!read && !is_device_)
      return Status::Failed(url_ + ": end of the video after " + std::to_string(frames_) + " frames");
    if (!read) return Status::Failed(url_ + ": no frame (dropped, or the device stopped streaming)");
    if (frame.empty()) return Status::Failed(url_ + ": empty frame");
    if (waited_ms > static_cast<double>(timeout.count()))
      return Status::Failed(url_ + ": no frame within " + std::to_string(timeout.count()) + " ms (waited " +
                            std::to_string(static_cast<long>(waited_ms)) + " ms)");
    ++frames_;
    return frame;
  }

  std::string Describe() const override {
    return url_ + " (" + std::to_string(static_cast<int>(capture_->Get(cv::CAP_PROP_FRAME_WIDTH))) + "x" +
           std::to_string(static_cast<int>(capture_->Get(cv::CAP_PROP_FRAME_HEIGHT))) + ", " +
           capture_->BackendName() + ")";
  }

  Status SetExposure(double microseconds) override {
    // V4L2's exposure_absolute is in units of 100 µs.
    if (is_device_ && capture_->Set(cv::CAP_PROP_EXPOSURE, microseconds / 100)) return Status::Ok();
    return FrameSource::SetExposure(microseconds);
  }
  Status SetGain(double decibels) override {
    if (is_device_ && capture_->Set(cv::CAP_PROP_GAIN, decibels)) return Status::Ok();
    return FrameSource::SetGain(decibels);
  }

 private:
  std::string url_;
  std::unique_ptr<VideoStream> capture_;
  bool is_device_;
  int frames_ = 0;
};

bool IsStillImage(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* image : {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".pgm", ".ppm"})
    if (ext == image) return true;
  return false;
}

}  // namespace

Status BadFrameSourceUrl(const std::string& url, const std::string& problem) {
  return Status::BadInput("camera '" + url + "': " + problem + "; accepted forms: " + kFrameSourceForms);
}

StatusOr<std::unique_ptr<FrameSource>> OpenFileFrameSource(const std::string& url, const std::string& path) {
  if (path.empty()) return BadFrameSourceUrl(url, "no path after 'file:'");
  // A FIFO or /dev/zero said "no such file"; a video has no size cap of its own.
  if (Status s = CheckFileForReading(path, std::numeric_limits<size_t>::max()); !s.ok()) return s.Prefixed(url + ": ");
  if (IsStillImage(path)) {
    StatusOr<cv::Mat> image = ReadImageFile(path);
    if (!image.ok()) return image.status().Prefixed(url + ": ");
    return std::unique_ptr<FrameSource>(std::make_unique<StillImageSource>(url, *image));
  }
  StatusOr<std::unique_ptr<VideoStream>> capture = OpenVideoFile(path);
  if (!capture.ok()) return capture.status().Prefixed(url + ": ");
  return std::unique_ptr<FrameSource>(std::make_unique<CaptureSource>(url, std::move(*capture), false));
}

StatusOr<std::unique_ptr<FrameSource>> OpenV4l2FrameSource(const std::string& url, const std::string& device) {
  const bool digits = !device.empty() && device.size() <= 3 &&
                      std::all_of(device.begin(), device.end(), [](unsigned char c) { return std::isdigit(c); });
  if (!digits) return BadFrameSourceUrl(url, "expected a device number after 'v4l2:' (v4l2:0 is /dev/video0)");
  StatusOr<std::unique_ptr<VideoStream>> capture = OpenVideoDevice(std::stoi(device), cv::CAP_V4L2);
  if (!capture.ok())
    return Status::IoError(url + ": cannot open /dev/video" + device +
                           " (not connected, no permission, or used by another program)");
  return std::unique_ptr<FrameSource>(std::make_unique<CaptureSource>(url, std::move(*capture), true));
}

Status FrameSource::SetExposure(double) {
  return Status::BadInput(Describe() + ": setting the exposure is not supported by this camera");
}

Status FrameSource::SetGain(double) {
  return Status::BadInput(Describe() + ": setting the gain is not supported by this camera");
}

}  // namespace hexcal::workflow

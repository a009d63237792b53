#include "devices/fake_genicam_camera.h"

#include <arpa/inet.h>
#include <arv.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "devices/glib_handles.h"

namespace hexcal::workflow {
namespace {

constexpr int kGvcpPort = 3956;          // GigE Vision's control port, where the camera listens
constexpr size_t kMaxSerialLength = 15;  // the bootstrap register holds 16 bytes with the terminator

// Whether another process (or camera) already holds the control port of an
// IPv4 address. Aravis binds it without SO_REUSEADDR and only warns when that
// fails, so without this check a second camera would start and never answer.
// A name rather than an address is not checked.
Status CheckControlPortFree(const std::string& interface) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(kGvcpPort);
  if (inet_pton(AF_INET, interface.c_str(), &address.sin_addr) != 1) return Status::Ok();
  const int probe = socket(AF_INET, SOCK_DGRAM, 0);
  if (probe < 0)
    return Status::IoError("fake GenICam camera: cannot open a UDP socket: " + std::string(strerror(errno)));
  const int bound = bind(probe, reinterpret_cast<const sockaddr*>(&address), sizeof(address));
  const int bind_errno = errno;
  close(probe);
  if (bound == 0) return Status::Ok();
  if (bind_errno == EADDRINUSE)
    return Status::Busy("fake GenICam camera: " + interface + ":" + std::to_string(kGvcpPort) +
                        " is in use: another GigE Vision camera serves this address (one per address)");
  return Status::IoError("fake GenICam camera: cannot serve on " + interface + ": " + strerror(bind_errno));
}

Status CheckOptions(const FakeCameraOptions& options, const std::function<cv::Mat()>& render) {
  if (!render) return Status::BadInput("fake GenICam camera: no render function");
  if (options.interface.empty()) return Status::BadInput("fake GenICam camera: no interface address");
  if (options.serial.empty() || options.serial.size() > kMaxSerialLength)
    return Status::BadInput("fake GenICam camera: the serial '" + options.serial + "' must have 1 to 15 characters");
  if (options.width < 0 || options.height < 0 || (options.width == 0) != (options.height == 0))
    return Status::BadInput(
        "fake GenICam camera: width and height must both be positive, or both 0 (from the first "
        "frame), not " +
        std::to_string(options.width) + "x" + std::to_string(options.height));
  if (!(options.lost_packet_ratio >= 0 && options.lost_packet_ratio <= 1))
    return Status::BadInput("fake GenICam camera: lost_packet_ratio must be in [0, 1]");
  return Status::Ok();
}

}  // namespace

struct FakeGenICamCamera::Impl {
  std::function<cv::Mat()> render;
  int width = 0, height = 0;
  std::string device_id;
  std::atomic<long> black_frames{0};   // render results of another size or type
  GObjectPtr<ArvGvFakeCamera> camera;  // declared last: destroyed (its thread joined) before `render`

  // ArvFakeCameraFillPattern: called by arv_fake_camera_fill_buffer on the
  // simulator's thread, after it has set the buffer's size, format and
  // timestamp, with a buffer of at least Width x Height bytes.
  static void Fill(ArvBuffer* buffer, void* self, guint32 /*exposure_us*/, guint32 /*gain*/, ArvPixelFormat format) {
    auto* impl = static_cast<Impl*>(self);
    size_t unused = 0;  // the data pointer is the buffer's start; its received size is not set yet
    void* pixels = const_cast<void*>(arv_buffer_get_data(buffer, &unused));
    const int width = arv_buffer_get_image_width(buffer), height = arv_buffer_get_image_height(buffer);
    if (pixels == nullptr || format != ARV_PIXEL_FORMAT_MONO_8 || width != impl->width || height != impl->height) {
      ++impl->black_frames;  // a client changed the format or the region: leave the buffer as it is
      return;
    }
    cv::Mat frame(height, width, CV_8UC1, pixels);
    cv::Mat image;
    try {
      image = impl->render();
    } catch (...) {  // an exception must not unwind through Aravis' C thread
      image.release();
    }
    if (image.type() == CV_8UC1 && image.cols == width && image.rows == height) {
      image.copyTo(frame);
    } else {
      frame.setTo(0);
      ++impl->black_frames;
    }
  }
};

FakeGenICamCamera::FakeGenICamCamera(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

FakeGenICamCamera::~FakeGenICamCamera() { impl_->camera.reset(); }

std::string FakeGenICamCamera::DeviceId() const { return impl_->device_id; }

StatusOr<std::unique_ptr<FakeGenICamCamera>> FakeGenICamCamera::Start(const FakeCameraOptions& options,
                                                                      std::function<cv::Mat()> render) {
  if (Status valid = CheckOptions(options, render); !valid.ok()) return valid;
  auto impl = std::make_unique<Impl>();
  impl->width = options.width;
  impl->height = options.height;
  if (impl->width == 0) {
    const cv::Mat first = render();
    if (first.empty() || first.type() != CV_8UC1)
      return Status::BadInput("fake GenICam camera: the render function must return a CV_8UC1 image");
    impl->width = first.cols;
    impl->height = first.rows;
  }
  impl->render = std::move(render);
  if (Status free = CheckControlPortFree(options.interface); !free.ok()) return free;

  impl->camera.reset(arv_gv_fake_camera_new(options.interface.c_str(), options.serial.c_str()));
  if (!impl->camera || !arv_gv_fake_camera_is_running(impl->camera.get()))
    return Status::IoError("fake GenICam camera: no network interface with the address or name '" + options.interface +
                           "'");
  ArvFakeCamera* registers = arv_gv_fake_camera_get_fake_camera(impl->camera.get());
  // No client is connected yet, so the simulator's thread reads none of these.
  const std::pair<guint32, guint32> writes[] = {{ARV_FAKE_CAMERA_REGISTER_SENSOR_WIDTH, impl->width},
                                                {ARV_FAKE_CAMERA_REGISTER_SENSOR_HEIGHT, impl->height},
                                                {ARV_FAKE_CAMERA_REGISTER_WIDTH, impl->width},
                                                {ARV_FAKE_CAMERA_REGISTER_HEIGHT, impl->height},
                                                {ARV_FAKE_CAMERA_REGISTER_X_OFFSET, 0},
                                                {ARV_FAKE_CAMERA_REGISTER_Y_OFFSET, 0},
                                                {ARV_FAKE_CAMERA_REGISTER_PIXEL_FORMAT, ARV_PIXEL_FORMAT_MONO_8}};
  for (const auto& [address, value] : writes)
    if (!arv_fake_camera_write_register(registers, address, value))
      return Status::Failed("fake GenICam camera: cannot write register " + std::to_string(address));
  g_object_set(impl->camera.get(), "gvsp-lost-ratio", options.lost_packet_ratio, nullptr);
  arv_fake_camera_set_fill_pattern(registers, &Impl::Fill, impl.get());
  // Aravis' GigE Vision interface names a device "<vendor>-<model>-<serial>".
  impl->device_id = "Aravis-Fake-" + options.serial;
  return std::unique_ptr<FakeGenICamCamera>(new FakeGenICamCamera(std::move(impl)));
}

}  // namespace hexcal::workflow

// The aravis: camera against Aravis' own GigE Vision simulator on loopback
// (devices/aravis_frame_source.h, devices/fake_genicam_camera.h): frames
// arrive byte-identical, a grab never returns a frame from before it, errors
// name the URL, bad options are bad input, and time-outs and incomplete frames
// are named. Each frame carries the number of the render call that made it in
// its first four pixels, so a test can tell which frame it got and when that
// frame was made.
#include "devices/aravis_frame_source.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <regex>
#include <thread>

#include "devices/device_urls.h"
#include "devices/fake_genicam_camera.h"
#include "devices/frame_source.h"

namespace hexcal::workflow {
namespace {

using std::chrono::milliseconds;

constexpr int kWidth = 320, kHeight = 240;

// A gradient that depends on the scene, with the render number burned into
// pixels 0..3 (little endian).
cv::Mat SceneFrame(uint32_t render_number, int scene) {
  cv::Mat frame(kHeight, kWidth, CV_8UC1);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) frame.at<uint8_t>(y, x) = static_cast<uint8_t>(x + 2 * y + 97 * scene);
  std::memcpy(frame.data, &render_number, sizeof(render_number));
  return frame;
}

uint32_t RenderNumber(const cv::Mat& frame) {
  uint32_t number = 0;
  std::memcpy(&number, frame.data, sizeof(number));
  return number;
}

bool SameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::countNonZero(a != b) == 0;
}

// What the fake camera shows; the test thread changes `scene`.
struct Scene {
  std::atomic<int> scene{0};
  std::atomic<uint32_t> renders{0};
  cv::Mat Render() { return SceneFrame(renders++, scene.load()); }
};

class AravisFrameSourceTest : public ::testing::Test {
 protected:
  // The fake camera on loopback, or nullptr with the reason when this machine
  // cannot serve one there (then the test skips).
  std::unique_ptr<FakeGenICamCamera> StartFake(FakeCameraOptions options = {}) {
    StatusOr<std::unique_ptr<FakeGenICamCamera>> fake =
        FakeGenICamCamera::Start(options, [this] { return scene_.Render(); });
    if (fake.ok()) return std::move(*fake);
    why_not_ = fake.status().message();
    const StatusKind kind = fake.status().kind();
    if (kind != StatusKind::kIo && kind != StatusKind::kBusy) ADD_FAILURE() << why_not_;
    return nullptr;
  }

  std::unique_ptr<FrameSource> Open(const FakeGenICamCamera& fake, const std::string& options = "") {
    StatusOr<std::unique_ptr<FrameSource>> source = OpenFrameSource("aravis:" + fake.DeviceId() + options);
    EXPECT_TRUE(source.ok()) << source.status().message();
    return source.ok() ? std::move(*source) : nullptr;
  }

  Scene scene_;
  std::string why_not_;
};

#define START_FAKE_OR_SKIP(name, options)                       \
  std::unique_ptr<FakeGenICamCamera> name = StartFake(options); \
  if (!name) GTEST_SKIP() << "no fake GigE Vision camera on loopback: " << why_not_

TEST_F(AravisFrameSourceTest, FramesArriveByteIdenticalAndStartedAfterTheGrab) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  EXPECT_EQ(fake->DeviceId(), "Aravis-Fake-HEXCAL01");
  std::unique_ptr<FrameSource> camera = Open(*fake);
  ASSERT_TRUE(camera);
  EXPECT_NE(camera->Describe().find("aravis:Aravis-Fake-HEXCAL01 (Aravis Fake HEXCAL01, 320x240 Mono8)"),
            std::string::npos)
      << camera->Describe();
  double total_ms = 0, max_ms = 0;
  constexpr int kGrabs = 8;
  for (int k = 0; k < kGrabs; ++k) {
    std::this_thread::sleep_for(milliseconds(100));  // the robot moves; frames queue up
    const uint32_t renders_before = scene_.renders.load();
    const auto start = std::chrono::steady_clock::now();
    StatusOr<cv::Mat> frame = camera->Grab(milliseconds(2000));
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(frame.ok()) << frame.status().message();
    total_ms += ms;
    max_ms = std::max(max_ms, ms);
    const uint32_t number = RenderNumber(*frame);
    EXPECT_GE(number, renders_before) << "grab " << k << " returned a frame rendered before it was called";
    EXPECT_TRUE(SameBytes(*frame, SceneFrame(number, 0))) << "grab " << k;
  }
  std::cout << "grab: mean " << total_ms / kGrabs << " ms, max " << max_ms << " ms (" << kGrabs << " grabs)\n";
  RecordProperty("grab_mean_ms", std::to_string(total_ms / kGrabs));
  EXPECT_LT(max_ms, 1000);
}

TEST_F(AravisFrameSourceTest, AGrabAfterTheSceneChangesReturnsTheNewSceneNotABufferedFrame) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  std::unique_ptr<FrameSource> camera = Open(*fake);
  ASSERT_TRUE(camera);
  for (int scene = 1; scene <= 3; ++scene) {
    // Every stream buffer fills with the old scene while nobody grabs (a
    // robot move); then the scene changes and the grab comes.
    std::this_thread::sleep_for(milliseconds(250));
    scene_.scene = scene;
    StatusOr<cv::Mat> frame = camera->Grab(milliseconds(2000));
    ASSERT_TRUE(frame.ok()) << frame.status().message();
    EXPECT_TRUE(SameBytes(*frame, SceneFrame(RenderNumber(*frame), scene)))
        << "scene " << scene << ": got a frame of another scene";
  }
}

TEST_F(AravisFrameSourceTest, AMissingCameraNamesTheUrlAndListsTheCamerasAravisSees) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  StatusOr<std::unique_ptr<FrameSource>> missing = OpenFrameSource("aravis:No-Such-Camera");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().kind(), StatusKind::kBadInput);
  const std::string& message = missing.status().message();
  EXPECT_NE(message.find("camera 'aravis:No-Such-Camera': no GenICam camera 'No-Such-Camera'; Aravis sees: "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(fake->DeviceId() + " (127.0.0.1)"), std::string::npos) << message;
}

TEST(AravisUrl, BadOptionsAreBadInputNamingTheUrl) {
  const auto refused = [](const std::string& url, const std::string& expected) {
    StatusOr<std::unique_ptr<FrameSource>> source = OpenFrameSource(url);
    ASSERT_FALSE(source.ok()) << url;
    EXPECT_EQ(source.status().kind(), StatusKind::kBadInput) << url;
    EXPECT_NE(source.status().message().find("camera '" + url + "': " + expected), std::string::npos)
        << source.status().message();
  };
  refused("aravis:Cam?exposure=fast", "exposure 'fast' is not a number");
  refused("aravis:Cam?exposure=", "exposure '' is not a number");
  refused("aravis:Cam?exposure=-5", "exposure '-5' must be a positive number of microseconds");
  refused("aravis:Cam?gain=1&gain=2", "'gain' given twice");
  refused("aravis:Cam?shutter=3", "unknown option 'shutter' (exposure, gain)");
  refused("aravis:", "no camera name after 'aravis:'");
  refused("aravis:?exposure=10", "no camera name after 'aravis:'");

  StatusOr<AravisUrl> parsed = ParseAravisUrl("aravis:Aravis-Fake-GV01?exposure=8000&gain=2.5");
  ASSERT_TRUE(parsed.ok()) << parsed.status().message();
  EXPECT_EQ(parsed->device_id, "Aravis-Fake-GV01");
  EXPECT_EQ(parsed->exposure_us, 8000.0);
  EXPECT_EQ(parsed->gain_db, 2.5);
}

TEST_F(AravisFrameSourceTest, ExposureAndGainAreSetOrRefusedOutsideTheCamerasRange) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  StatusOr<std::unique_ptr<FrameSource>> too_long = OpenFrameSource("aravis:" + fake->DeviceId() + "?exposure=1e9");
  ASSERT_FALSE(too_long.ok());
  EXPECT_EQ(too_long.status().kind(), StatusKind::kBadInput);
  EXPECT_NE(too_long.status().message().find("exposure 1e+09 µs is outside the camera's range [10, 1e+07] µs"),
            std::string::npos)
      << too_long.status().message();

  std::unique_ptr<FrameSource> camera = Open(*fake, "?exposure=20000&gain=2");
  ASSERT_TRUE(camera);
  EXPECT_TRUE(camera->SetExposure(5000).ok());
  EXPECT_TRUE(camera->SetGain(4).ok());
  const Status bad_gain = camera->SetGain(100);
  EXPECT_EQ(bad_gain.kind(), StatusKind::kBadInput);
  EXPECT_NE(bad_gain.message().find("gain 100 is outside the camera's range [0, 10]"), std::string::npos)
      << bad_gain.message();
  EXPECT_EQ(camera->SetExposure(-1).kind(), StatusKind::kBadInput);
  StatusOr<cv::Mat> frame = camera->Grab(milliseconds(2000));  // still streaming after the changes
  ASSERT_TRUE(frame.ok()) << frame.status().message();
}

TEST_F(AravisFrameSourceTest, AGrabShorterThanAFrameTimesOutWithANamedError) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  std::unique_ptr<FrameSource> camera = Open(*fake);
  ASSERT_TRUE(camera);
  // 25 fps and 10 ms of exposure: no frame can start and arrive within 20 ms.
  const auto start = std::chrono::steady_clock::now();
  StatusOr<cv::Mat> frame = camera->Grab(milliseconds(20));
  const double waited_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().kind(), StatusKind::kFailed);
  EXPECT_NE(frame.status().message().find("aravis:" + fake->DeviceId() +
                                          ": no complete frame started after the request within 20 ms"),
            std::string::npos)
      << frame.status().message();
  EXPECT_LT(waited_ms, 500);
  StatusOr<cv::Mat> next = camera->Grab(milliseconds(2000));
  EXPECT_TRUE(next.ok()) << next.status().message();
}

TEST_F(AravisFrameSourceTest, IncompleteFramesAreRequeuedCountedAndNamed) {
  FakeCameraOptions lossy;
  lossy.lost_packet_ratio = 0.2;  // ~56 packets a frame: practically none arrives whole
  START_FAKE_OR_SKIP(fake, lossy);
  std::unique_ptr<FrameSource> camera = Open(*fake);
  ASSERT_TRUE(camera);
  StatusOr<cv::Mat> frame = camera->Grab(milliseconds(800));
  ASSERT_FALSE(frame.ok());
  EXPECT_EQ(frame.status().kind(), StatusKind::kFailed);
  std::smatch match;
  const std::string message = frame.status().message();
  ASSERT_TRUE(std::regex_search(message, match, std::regex(R"(within 800 ms \((\d+) incomplete frames)"))) << message;
  EXPECT_GE(std::stoi(match[1]), 3) << message;
  std::cout << message << "\n";
}

TEST_F(AravisFrameSourceTest, OneFakeCameraPerAddress) {
  START_FAKE_OR_SKIP(fake, FakeCameraOptions{});
  FakeCameraOptions second;
  second.serial = "HEXCAL02";
  StatusOr<std::unique_ptr<FakeGenICamCamera>> other =
      FakeGenICamCamera::Start(second, [] { return cv::Mat(4, 4, CV_8UC1); });
  ASSERT_FALSE(other.ok());
  EXPECT_EQ(other.status().kind(), StatusKind::kBusy);
  EXPECT_NE(other.status().message().find("127.0.0.1:3956 is in use"), std::string::npos) << other.status().message();
}

TEST(FakeGenICamCamera, OptionsAreChecked) {
  FakeCameraOptions long_serial;
  long_serial.serial = "A-SERIAL-OF-20-CHARS";
  const auto render = [] { return cv::Mat(4, 4, CV_8UC1); };
  EXPECT_EQ(FakeGenICamCamera::Start(long_serial, render).status().kind(), StatusKind::kBadInput);
  FakeCameraOptions half_size;
  half_size.width = 64;
  EXPECT_EQ(FakeGenICamCamera::Start(half_size, render).status().kind(), StatusKind::kBadInput);
  EXPECT_EQ(FakeGenICamCamera::Start({}, [] { return cv::Mat(4, 4, CV_8UC3); }).status().kind(), StatusKind::kBadInput);
  EXPECT_EQ(FakeGenICamCamera::Start({}, nullptr).status().kind(), StatusKind::kBadInput);
}

}  // namespace
}  // namespace hexcal::workflow

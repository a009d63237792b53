// The `aravis:` camera of devices/frame_source.h: GenICam cameras (GigE
// Vision, USB3 Vision) through libaravis 0.8. OpenFrameSource calls it for
// URLs of the form
//
//   aravis:NAME[?exposure=US][&gain=DB]
//
// NAME is the device id as `arv-tool-0.8` lists it ("Aravis-Fake-GV01",
// "Basler-21234567"); exposure is in microseconds, gain in dB (the camera's
// Gain feature; a camera with only GainRaw takes its raw number). Values
// outside the camera's range are refused, not clamped.
//
//   StatusOr<std::unique_ptr<FrameSource>> camera = OpenFrameSource("aravis:Aravis-Fake-GV01?exposure=8000");
//   StatusOr<cv::Mat> frame = (*camera)->Grab(std::chrono::seconds(2));  // started after this call
//
// The camera runs free (continuous acquisition, Mono8 where it has it) from
// the open on; Grab throws away every frame that was already waiting or that
// may have started before the call, so a frame taken after a robot move shows
// the robot where it stopped (the rule and what it relies on: Grab in
// aravis_frame_source.cc). GigE Vision streams go through a plain UDP socket
// with a fixed 4 MiB buffer, the settings that deliver every frame on
// loopback (../shared/devices.md).
//
// Built only where Aravis is found (HEXCAL_HAVE_ARAVIS); without it
// OpenFrameSource refuses `aravis:` URLs and says what to install.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "devices/frame_source.h"

namespace hexcal::workflow {

struct AravisUrl {
  std::string device_id;              // Aravis' device id, as arv-tool-0.8 lists it
  std::optional<double> exposure_us;  // ?exposure=, microseconds
  std::optional<double> gain_db;      // ?gain=, dB
};

// Splits and checks an `aravis:` URL; bad input names the URL and the problem.
StatusOr<AravisUrl> ParseAravisUrl(const std::string& url);

// Opens and starts the camera. A name Aravis does not know is bad input
// whose message lists the cameras it sees.
StatusOr<std::unique_ptr<FrameSource>> OpenAravisFrameSource(const std::string& url);

// The cameras Aravis finds now, as "ID (ADDRESS)"; a discovery takes ~1 s.
std::vector<std::string> ListAravisCameras();

}  // namespace hexcal::workflow

#include "devices/device_urls.h"

#include "devices/linuxcnc_controller.h"

#ifdef HEXCAL_HAVE_ARAVIS
#include "devices/aravis_frame_source.h"
#endif

namespace hexcal::workflow {
namespace {

Status BadControllerUrl(const std::string& url, const std::string& problem) {
  return Status::BadInput("controller '" + url + "': " + problem + "; accepted forms: " + kControllerForms);
}

}  // namespace

StatusOr<std::unique_ptr<Controller>> OpenController(const std::string& url, const ControllerOptions& options) {
  if (url == "sim") {
    if (!options.sim) return Status::BadInput("controller 'sim' needs the session's sim world (OpenAcquisitionRig)");
    return options.sim();
  }
  if (url.rfind("linuxcnc://", 0) == 0) {
    StatusOr<LinuxCncAddress> address = ParseLinuxCncUrl(url);
    if (!address.ok()) return address.status();
    if (!options.robot)
      return Status::BadInput("controller '" + url + "' needs the session's robot (OpenAcquisitionRig)");
    return OpenLinuxCncController(*address, *options.robot);
  }
  return BadControllerUrl(url, url.empty() ? "empty URL" : "unknown kind");
}

StatusOr<std::unique_ptr<FrameSource>> OpenFrameSource(const std::string& url, const FrameSourceOptions& options) {
  if (url == "sim") {
    if (!options.sim) return Status::BadInput("camera 'sim' looks at the sim world: use it with --controller sim");
    return options.sim();
  }
  const size_t colon = url.find(':');
  const std::string scheme = colon == std::string::npos ? url : url.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : url.substr(colon + 1);
  if (scheme == "file") return OpenFileFrameSource(url, rest);
  if (scheme == "v4l2") return OpenV4l2FrameSource(url, rest);
  if (scheme == "aravis") {
#ifdef HEXCAL_HAVE_ARAVIS
    return OpenAravisFrameSource(url);
#else
    return Status::BadInput("camera '" + url +
                            "': this hexcal was built without Aravis (install libaravis-dev: scripts/install-deps.sh)");
#endif
  }
  return BadFrameSourceUrl(url, url.empty() ? "empty URL" : "unknown kind '" + scheme + "'");
}

}  // namespace hexcal::workflow

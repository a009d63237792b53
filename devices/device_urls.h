// Controllers and cameras opened by URL (docs/acquisition.md): the one place
// that knows every kind, above the devices themselves, so that no device
// module includes another (issue 37: controller.cc and frame_source.cc
// included the LinuxCNC, Aravis and sim devices that include them back).
//
//   controllers  sim, linuxcnc://HOST:PORT               (kControllerForms)
//   cameras      sim, v4l2:N, file:PATH, aravis:NAME...  (kFrameSourceForms)
//
//   StatusOr<std::unique_ptr<Controller>> robot = OpenController("sim", SimControllerOptions(world));
//   StatusOr<std::unique_ptr<FrameSource>> camera = OpenFrameSource("v4l2:0");
#pragma once

#include <memory>
#include <string>

#include "core/status.h"
#include "devices/controller.h"
#include "devices/frame_source.h"

namespace hexcal::workflow {

StatusOr<std::unique_ptr<Controller>> OpenController(const std::string& url, const ControllerOptions& options = {});
StatusOr<std::unique_ptr<FrameSource>> OpenFrameSource(const std::string& url, const FrameSourceOptions& options = {});

}  // namespace hexcal::workflow

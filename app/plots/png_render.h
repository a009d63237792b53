// SVG to PNG with Qt, offscreen: works without a display. If the process has
// no QGuiApplication yet, one is created for the call with
// QT_QPA_PLATFORM=offscreen (set before it exists); call from the main thread.
// Only app-level code links Qt; core never does.
//
//   Status written = WriteSvgAsPng(BarChartSvg(options, bars), "fig14.png", 760, 460);
#pragma once

#include <string>

#include "core/status.h"

namespace hexcal::plots {

// Renders `svg` onto a white width x height image and writes it atomically as PNG.
Status WriteSvgAsPng(const std::string& svg, const std::string& path, int width, int height);

}  // namespace hexcal::plots

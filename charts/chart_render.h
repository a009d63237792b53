// A ChartSpec drawn offscreen into files: SVG through QSvgGenerator, PNG
// through a QImage, both from the same QChart as the GUI shows (qt_chart.h).
// The HTML report inlines ChartSvgElement(); `hexcal simulate --plots` writes
// WriteChartFiles().
//
// Qt needs a QApplication for charts (they are QGraphicsWidgets). In the GUI
// the process has one. In the CLI, the first call creates one that lives as
// long as the process, with QT_QPA_PLATFORM=offscreen when the variable is
// unset (or names xcb/wayland with no display to open), so no display is
// needed; its start-up chatter is silenced and the C locale that Qt would
// change is restored.
//
// Thread: call only on the thread that owns the QApplication (the GUI
// thread; in the CLI, the thread of the first call). Any other thread gets an
// error, not a render: Qt's widgets and fonts are not thread-safe.
//
//   StatusOr<std::string> svg = ChartSvgElement(LegReadingsChart(robot, plan));
//   std::vector<std::string> written;
//   Status s = WriteChartFiles(Fig14Chart(result, "mm"), "plots", "fig14", &written);  // fig14.svg, fig14.png
#pragma once

#include <string>
#include <vector>

#include "charts/chart_spec.h"
#include "core/status.h"

namespace hexcal::charts {

// A standalone SVG document (XML declaration, spec.width x spec.height px).
StatusOr<std::string> ChartSvg(const ChartSpec& spec);
// The <svg> element alone, sized in pixels, for inlining in an HTML page.
StatusOr<std::string> ChartSvgElement(const ChartSpec& spec);
// PNG bytes of spec.width x spec.height pixels on white.
StatusOr<std::string> ChartPng(const ChartSpec& spec);

// Before a command writes figures: DIRECTORY/STEM.svg and .png for each stem
// must not exist unless `force` (CheckOutputFree, core/atomic_file.h).
Status CheckChartFilesFree(const std::string& directory, const std::vector<std::string>& stems, bool force);
// A `--plots` folder, created if missing.
Status CreatePlotsFolder(const std::string& directory);

// Writes DIRECTORY/STEM.svg and DIRECTORY/STEM.png atomically (the folder
// must exist) and appends each path written to `written`.
Status WriteChartFiles(const ChartSpec& spec, const std::string& directory, const std::string& stem,
                       std::vector<std::string>* written);

}  // namespace hexcal::charts

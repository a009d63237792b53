// The window as a PNG: the widgets plus the 3D view's framebuffer (the GL
// widget is drawn into the grab by Qt). For --screenshot, tests and docs/.
//
//   SaveWindowScreenshot(&window, "docs/images/gui-plan.png");
#pragma once

#include <QString>

class QWidget;

namespace hexcal::ui {

// Lets pending events and the worker-free refreshes settle, then grabs.
bool SaveWindowScreenshot(QWidget* window, const QString& file);

}  // namespace hexcal::ui

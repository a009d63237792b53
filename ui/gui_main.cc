// hexcal-gui [SESSION]
// hexcal-gui --demo          opens the demo session (made by `hexcal demo` the first time)
// hexcal-gui --screenshot FILE [--panel robot|plan|acquire|measure|calibrate|validate|study] [--size 1280x720]
// [SESSION]
//   renders the window for SESSION to a PNG and exits (tests, docs/gui.md).
// hexcal-gui --controller sim --camera sim SESSION   connects the Acquire step's devices at start
#include <QVTKOpenGLNativeWidget.h>

#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <iostream>

#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/main_window.h"
#include "ui/screenshot.h"

int main(int argc, char** argv) {
  // Before QApplication: VTK needs its OpenGL core profile on every GL widget.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("hexcal-gui");
  QApplication::setOrganizationName("hexcal");
  QCommandLineParser parser;
  parser.setApplicationDescription("hexcal-gui: plan, measure, calibrate and validate a hexapod");
  parser.addHelpOption();
  parser.addOption({"screenshot", "Render the window to FILE (PNG) and exit.", "FILE"});
  parser.addOption(
      {"panel",
       "Panel to show: robot, plan, acquire, measure, calibrate, validate, study (the Validate step's study tab).",
       "NAME"});
  parser.addOption(
      {"size", "Window size, WIDTHxHEIGHT (default 1280x720; on screen, at most the screen's).", "WxH", "1280x720"});
  parser.addOption({"controller",
                    "Acquire step: connect this controller at start (sim, none), with --camera (a points session: "
                    "alone).",
                    "URL"});
  parser.addOption({"camera", "Acquire step: connect this camera at start (sim, v4l2:N, file:PATH).", "URL"});
  parser.addOption({"demo", "Open the demo session (hexcal demo makes it the first time, about 15 s)."});
  parser.addPositionalArgument("session", "A session folder (hexcal session init, or File > New).");
  parser.process(app);

  const QString screenshot = parser.value("screenshot");
  hexcal::ui::SetInteractive(screenshot.isEmpty());
  hexcal::ui::MainWindow window;
  if (!parser.positionalArguments().isEmpty() && !window.OpenSession(parser.positionalArguments().front()) &&
      !screenshot.isEmpty())
    return 2;
  if (parser.isSet("panel") && !window.ShowPanelNamed(parser.value("panel"))) {
    std::cerr << "hexcal-gui: --panel: '" << parser.value("panel").toStdString()
              << "' is not robot, plan, acquire, measure, calibrate, validate or study\n";
    return 2;
  }
  const QStringList size = parser.value("size").split('x');
  if (size.size() != 2 || size[0].toInt() < 320 || size[1].toInt() < 240) {
    std::cerr << "hexcal-gui: --size: '" << parser.value("size").toStdString() << "' is not WIDTHxHEIGHT (e.g. 1280x720)\n";
    return 2;
  }
  // A screenshot is exactly the size asked for; on screen the window stays within the screen.
  const QSize wanted(size[0].toInt(), size[1].toInt());
  if (screenshot.isEmpty()) {
    window.FitScreen(wanted);
  } else {
    window.resize(wanted);
  }
  window.show();
  // A points session has no camera to name: its controller connects alone.
  const bool devices = parser.isSet("camera") || (parser.isSet("controller") && window.Session()->IsPointsSession());
  if (devices && window.Session()->IsOpen())
    window.Acquire()->Connect(parser.value("controller").isEmpty() ? "none" : parser.value("controller"),
                              parser.value("camera"));
  // A screenshot shows the devices connected and a live frame, not "connecting".
  while (!screenshot.isEmpty() && window.Acquire()->Job()->Running())
    app.processEvents(QEventLoop::AllEvents, 50);
  if (parser.isSet("demo")) window.OpenDemoSession();
  if (!screenshot.isEmpty()) {
    if (!hexcal::ui::SaveWindowScreenshot(&window, screenshot)) {
      std::cerr << "hexcal-gui: could not write " << screenshot.toStdString() << "\n";
      return 1;
    }
    return 0;
  }
  return app.exec();
}

#include "app/plots/png_render.h"

#include <QBuffer>
#include <QByteArray>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <QSvgRenderer>
#include <QtGlobal>
#include <memory>

#include "core/atomic_file.h"

namespace hexcal::plots {
namespace {

// Qt's notes about the headless session it is asked for ("XDG_RUNTIME_DIR not
// set", ...) are not the user's business; critical messages still pass.
void QuietHandler(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (type == QtCriticalMsg || type == QtFatalMsg) qt_message_output(type, context, message);
}

// A QGuiApplication for the duration of a render, when the process has none,
// with Qt's chatter silenced until it is gone.
class OffscreenSession {
 public:
  OffscreenSession() {
    if (QCoreApplication::instance() != nullptr) return;
    qputenv("QT_QPA_PLATFORM", "offscreen");  // never open a display
    previous_handler_ = qInstallMessageHandler(QuietHandler);
    static int argc = 1;
    static char name[] = "hexcal";
    static char* argv[] = {name, nullptr};
    app_ = std::make_unique<QGuiApplication>(argc, argv);
  }
  ~OffscreenSession() {
    if (!app_) return;
    app_.reset();
    qInstallMessageHandler(previous_handler_);
  }
  OffscreenSession(const OffscreenSession&) = delete;
  OffscreenSession& operator=(const OffscreenSession&) = delete;

 private:
  QtMessageHandler previous_handler_ = nullptr;
  std::unique_ptr<QGuiApplication> app_;
};

}  // namespace

Status WriteSvgAsPng(const std::string& svg, const std::string& path, int width, int height) {
  if (width < 1 || height < 1) return Status::Error(path + ": image size must be positive");
  const OffscreenSession session;
  if (qobject_cast<QGuiApplication*>(QCoreApplication::instance()) == nullptr) {
    return Status::Error(path + ": rendering a PNG needs a QGuiApplication, and this process has another kind");
  }
  QSvgRenderer renderer(QByteArray::fromStdString(svg));
  if (!renderer.isValid()) return Status::Error(path + ": the chart is not valid SVG");
  QImage image(width, height, QImage::Format_ARGB32);
  image.fill(Qt::white);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setRenderHint(QPainter::TextAntialiasing);
  renderer.render(&painter);
  painter.end();
  QByteArray png;
  QBuffer buffer(&png);
  buffer.open(QIODevice::WriteOnly);
  if (!image.save(&buffer, "PNG")) return Status::Error(path + ": PNG encoding failed");
  return WriteFileAtomically(path, png.toStdString());
}

}  // namespace hexcal::plots

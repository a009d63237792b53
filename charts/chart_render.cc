#include "charts/chart_render.h"

#include <QApplication>
#include <QBuffer>
#include <QChart>
#include <QGraphicsScene>
#include <QImage>
#include <QPainter>
#include <QScreen>
#include <QSvgGenerator>
#include <QThread>
#include <clocale>
#include <filesystem>

#include "charts/qt_chart.h"
#include "core/atomic_file.h"

namespace hexcal::charts {
namespace {

// Qt's notes about the headless session it runs in ("XDG_RUNTIME_DIR not
// set", ...) are not the CLI user's business; critical messages still pass.
void QuietHandler(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (type == QtCriticalMsg || type == QtFatalMsg) qt_message_output(type, context, message);
}

// The CLI's QApplication, offscreen unless the user chose a platform. A
// platform that needs a display (xcb, wayland) without one would abort the
// process in Qt's start-up, so that choice falls back to offscreen too.
void CreateOffscreenApplication() {
  const QByteArray platform = qgetenv("QT_QPA_PLATFORM");
  const bool no_display = qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("WAYLAND_DISPLAY");
  if (platform.isEmpty() || (no_display && (platform.startsWith("xcb") || platform.startsWith("wayland")))) {
    qputenv("QT_QPA_PLATFORM", "offscreen");
  }
  // QCoreApplication sets the user's locale, which would give printf and
  // strtod a decimal comma for the rest of the run: keep the one we had.
  const std::string locale = std::setlocale(LC_ALL, nullptr);
  qInstallMessageHandler(QuietHandler);
  static int argc = 1;
  static char name[] = "hexcal";
  static char* argv[] = {name, nullptr};
  // Never deleted: destroying it at exit, after Qt's own globals, is unsafe.
  static QApplication* const application = new QApplication(argc, argv);
  (void)application;
  std::setlocale(LC_ALL, locale.c_str());
}

// A QApplication exists and this is its thread (see the header).
Status PrepareQt() {
  if (QCoreApplication::instance() == nullptr) CreateOffscreenApplication();
  const QCoreApplication* application = QCoreApplication::instance();
  if (qobject_cast<const QApplication*>(application) == nullptr) {
    return Status::Failed(std::string("drawing a chart needs a QApplication, and this process has a ") +
                          application->metaObject()->className());
  }
  if (QThread::currentThread() != application->thread()) {
    return Status::Failed("charts are drawn on the thread that owns the QApplication, not on a worker thread");
  }
  return Status::Ok();
}

// The logical resolution the chart's fonts are laid out with; the image and
// the SVG use it too, so that text keeps the size the layout made room for.
int LayoutDpi() {
  const QScreen* screen = QGuiApplication::primaryScreen();
  return screen != nullptr ? qRound(screen->logicalDotsPerInch()) : 96;
}

// The chart of `spec`, laid out at spec.width x spec.height in a scene of its own.
class ChartScene {
 public:
  explicit ChartScene(const ChartSpec& spec) : size_(spec.width, spec.height) {
    QtCharts::QChart* chart = NewQtChart(spec);
    scene_.addItem(chart);  // the scene owns it
    chart->setGeometry(0, 0, size_.width(), size_.height());
    // The legend and axes lay out on posted LayoutRequest events, which no
    // event loop delivers here.
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
  }
  void Paint(QPainter* painter) {
    const QRectF rect(QPointF(0, 0), size_);
    painter->fillRect(rect, Qt::white);
    scene_.render(painter, rect, rect);
  }
  QSize size() const { return size_; }

 private:
  QGraphicsScene scene_;
  QSize size_;
};

Status CheckSpec(const ChartSpec& spec) {
  std::string error;
  return spec.IsValid(&error) ? Status::Ok() : Status::Failed(error);
}

// QSvgGenerator gives the size in millimetres; a page lays charts out in pixels.
std::string WithPixelSize(std::string svg, QSize size) {
  const size_t tag = svg.find("<svg");
  const std::pair<std::string, int> attributes[] = {{" width=\"", size.width()}, {" height=\"", size.height()}};
  for (const auto& [attribute, value] : attributes) {
    const size_t start = svg.find(attribute, tag);
    const size_t end = start == std::string::npos ? start : svg.find('"', start + attribute.size());
    if (end == std::string::npos) continue;
    svg.replace(start, end + 1 - start, attribute + std::to_string(value) + "\"");
  }
  return svg;
}

// QSvgGenerator names the one font family Qt drew with, which a browser
// may not have ("DejaVu LGC Sans" on the offscreen platform): add fallbacks.
std::string WithFontFallbacks(const std::string& svg) {
  static const std::string kAttribute = "font-family=\"";
  std::string out;
  size_t at = 0;
  for (size_t start = svg.find(kAttribute, at); start != std::string::npos; start = svg.find(kAttribute, at)) {
    const size_t end = svg.find('"', start + kAttribute.size());
    if (end == std::string::npos) break;
    out.append(svg, at, end - at);
    out += ", DejaVu Sans, Arial, sans-serif";
    at = end;
  }
  out.append(svg, at, std::string::npos);
  return out;
}

// QSvgGenerator opens a <g> with the full pen and font state for every state
// change, and most are closed again with nothing drawn: two thirds of a
// chart's bytes, which the report inlines five times. Drops those.
std::string DropEmptyGroups(const std::string& svg) {
  std::string out;
  out.reserve(svg.size());
  size_t at = 0;
  for (size_t open = svg.find("<g ", at); open != std::string::npos; open = svg.find("<g ", at)) {
    const size_t open_end = svg.find('>', open);
    if (open_end == std::string::npos) break;
    const size_t next = svg.find_first_not_of(" \t\r\n", open_end + 1);
    const bool empty = next != std::string::npos && svg.compare(next, 4, "</g>") == 0;
    out.append(svg, at, (empty ? open : open_end + 1) - at);
    at = empty ? svg.find_first_not_of(" \t\r\n", next + 4) : open_end + 1;
    if (at == std::string::npos) at = svg.size();
  }
  out.append(svg, at, std::string::npos);
  return out;
}

}  // namespace

StatusOr<std::string> ChartSvg(const ChartSpec& spec) {
  if (Status s = CheckSpec(spec); !s.ok()) return s;
  if (Status s = PrepareQt(); !s.ok()) return s;
  ChartScene scene(spec);
  QBuffer buffer;
  buffer.open(QIODevice::WriteOnly);
  QSvgGenerator generator;
  generator.setOutputDevice(&buffer);
  generator.setSize(scene.size());
  generator.setViewBox(QRect(QPoint(0, 0), scene.size()));
  generator.setResolution(LayoutDpi());
  generator.setTitle(QString::fromStdString(spec.title).toHtmlEscaped());  // written into <title> as is
  generator.setDescription("hexcal chart");
  QPainter painter;
  if (!painter.begin(&generator)) return Status::Failed("chart '" + spec.title + "': cannot start an SVG painter");
  scene.Paint(&painter);
  painter.end();
  return WithPixelSize(WithFontFallbacks(DropEmptyGroups(buffer.data().toStdString())), scene.size());
}

StatusOr<std::string> ChartSvgElement(const ChartSpec& spec) {
  StatusOr<std::string> svg = ChartSvg(spec);
  if (!svg.ok()) return svg;
  const size_t tag = svg->find("<svg");
  return tag == std::string::npos ? *svg : svg->substr(tag);
}

StatusOr<std::string> ChartPng(const ChartSpec& spec) {
  if (Status s = CheckSpec(spec); !s.ok()) return s;
  if (Status s = PrepareQt(); !s.ok()) return s;
  ChartScene scene(spec);
  QImage image(scene.size(), QImage::Format_ARGB32_Premultiplied);
  const int dots_per_metre = qRound(LayoutDpi() / 0.0254);
  image.setDotsPerMeterX(dots_per_metre);
  image.setDotsPerMeterY(dots_per_metre);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setRenderHint(QPainter::TextAntialiasing);
  scene.Paint(&painter);
  painter.end();
  QByteArray png;
  QBuffer buffer(&png);
  buffer.open(QIODevice::WriteOnly);
  if (!image.save(&buffer, "PNG")) return Status::Failed("chart '" + spec.title + "': PNG encoding failed");
  return png.toStdString();
}

Status CheckChartFilesFree(const std::string& directory, const std::vector<std::string>& stems, bool force) {
  for (const std::string& stem : stems) {
    for (const char* extension : {".svg", ".png"}) {
      const std::string path = (std::filesystem::path(directory) / (stem + extension)).string();
      if (Status s = CheckOutputFree(path, force); !s.ok()) return s;
    }
  }
  return Status::Ok();
}

Status CreatePlotsFolder(const std::string& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) return FileSystemError(directory, "cannot create the plots folder", error.value());
  return Status::Ok();
}

Status WriteChartFiles(const ChartSpec& spec, const std::string& directory, const std::string& stem,
                       std::vector<std::string>* written) {
  const std::filesystem::path base = std::filesystem::path(directory) / stem;
  StatusOr<std::string> svg = ChartSvg(spec);
  if (!svg.ok()) return svg.status();
  if (Status s = WriteFileAtomically(base.string() + ".svg", *svg); !s.ok()) return s;
  written->push_back(base.string() + ".svg");
  StatusOr<std::string> png = ChartPng(spec);
  if (!png.ok()) return png.status();
  if (Status s = WriteFileAtomically(base.string() + ".png", *png); !s.ok()) return s;
  written->push_back(base.string() + ".png");
  return Status::Ok();
}

}  // namespace hexcal::charts

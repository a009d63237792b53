#include "ui/tests/gui_test_support.h"

#include "ui/error_dialog.h"

#include <QAbstractButton>
#include <QAbstractItemView>
#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QChartView>
#include <QComboBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QTabBar>
#include <QTableView>
#include <QThread>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>
#include <cstdio>

namespace hexcal::ui {

int RunGuiTests(int argc, char** argv, const char* name, QString* sessions_dir) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SESSIONS (made by ui/tests/make_session)\n", name);
    return 2;
  }
  *sessions_dir = argv[1];
  SetInteractive(false);
  return RUN_ALL_TESTS();
}
namespace {

std::string Describe(const QWidget* widget) {
  QString name = widget->objectName();
  if (const auto* button = qobject_cast<const QAbstractButton*>(widget)) name += " '" + button->text() + "'";
  if (const auto* label = qobject_cast<const QLabel*>(widget)) name += " '" + label->text().left(60) + "'";
  return (QString(widget->metaObject()->className()) + " " + name).toStdString();
}

std::string RectText(const QRect& r) {
  return QString("%1x%2%3%4%5%6")
      .arg(r.width())
      .arg(r.height())
      .arg(r.x() >= 0 ? "+" : "")
      .arg(r.x())
      .arg(r.y() >= 0 ? "+" : "")
      .arg(r.y())
      .toStdString();
}

// A scroll area made to scroll its content up and down (the Plan options),
// as opposed to a panel's, which must not need to.
bool ScrollsByDesign(const QWidget* viewport) {
  const auto* scroll = viewport ? qobject_cast<const QScrollArea*>(viewport->parentWidget()) : nullptr;
  return scroll && scroll->viewport() == viewport && scroll->objectName() != "panel_scroll";
}

// The first ancestor that cuts part of `widget` off, or null. Inside a
// scroll area made to scroll, only what is cut sideways counts, and from
// there up the part in view.
const QWidget* ClippingAncestor(const QWidget* widget, const QWidget* window) {
  QRect r = widget->rect();  // in the coordinates of `child`
  const QWidget* child = widget;
  for (const QWidget* a = widget->parentWidget(); a != nullptr; child = a, a = a->parentWidget()) {
    r.translate(child->mapToParent(QPoint(0, 0)));
    if (ScrollsByDesign(a)) {
      if (r.left() < 0 || r.right() > a->rect().right()) return a;
      r = r.intersected(a->rect());
      if (r.isEmpty()) return nullptr;  // scrolled out of view: nothing of it to cut
    } else if (!a->rect().contains(r)) {
      return a;
    }
    if (a == window) break;
  }
  return nullptr;
}

// A button or a field squeezed below the height its text needs.
void CheckSqueezed(const QWidget* control, std::vector<std::string>* problems) {
  if (qobject_cast<const QAbstractItemView*>(control) || qobject_cast<const QtCharts::QChartView*>(control)) return;
  // A table's corner button and a tab bar's arrows are sized by their owner.
  const QWidget* owner = control->parentWidget();
  if (qobject_cast<const QAbstractItemView*>(owner) || qobject_cast<const QTabBar*>(owner)) return;
  const int needed = control->minimumSizeHint().height();
  if (control->height() < needed)
    problems->push_back(Describe(control) + " is squeezed to " + std::to_string(control->height()) + " px of " +
                        std::to_string(needed));
}

bool IsControl(const QWidget* w) {
  // Scroll bars and the headers' sections belong to their view; a combo box's
  // or spin box's line edit to its box.
  if (qobject_cast<const QScrollBar*>(w) || qobject_cast<const QHeaderView*>(w)) return false;
  if (qobject_cast<const QLineEdit*>(w) &&
      (qobject_cast<const QComboBox*>(w->parentWidget()) || qobject_cast<const QAbstractSpinBox*>(w->parentWidget())))
    return false;
  return qobject_cast<const QAbstractButton*>(w) || qobject_cast<const QLineEdit*>(w) ||
         qobject_cast<const QComboBox*>(w) || qobject_cast<const QAbstractSpinBox*>(w) ||
         qobject_cast<const QAbstractSlider*>(w) || qobject_cast<const QtCharts::QChartView*>(w) ||
         qobject_cast<const QAbstractItemView*>(w);
}

// A table that shows fewer than kUsableRows of its rows is not usable.
void CheckTableHeight(const QTableView* table, std::vector<std::string>* problems) {
  const int rows = table->model() ? table->model()->rowCount() : 0;
  const int wanted = std::min(rows, kUsableRows) * table->verticalHeader()->defaultSectionSize();
  if (table->viewport()->height() < wanted)
    problems->push_back(Describe(table) + " shows " + std::to_string(table->viewport()->height()) +
                        " px of rows, fewer than " + std::to_string(std::min(rows, kUsableRows)) + " rows");
}

void CheckLabel(const QLabel* label, std::vector<std::string>* problems) {
  if (label->text().isEmpty() || !label->wordWrap()) return;
  // A label that is the whole of a scroll area (the verdict's findings) scrolls by design.
  const QWidget* viewport = label->parentWidget();
  const auto* scroll = viewport ? qobject_cast<const QScrollArea*>(viewport->parentWidget()) : nullptr;
  if (scroll && scroll->widget() == label) return;
  const int needed = label->heightForWidth(label->width());
  if (needed > label->height() + 1)
    problems->push_back(Describe(label) + " needs " + std::to_string(needed) + " px of height, has " +
                        std::to_string(label->height()));
}

}  // namespace

bool WaitFor(const std::function<bool()>& done, int timeout_ms) {
  QElapsedTimer timer;
  timer.start();
  while (!done()) {
    if (timer.elapsed() > timeout_ms) return false;
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(5);
  }
  QApplication::processEvents();
  return true;
}

QByteArray ReadBytes(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

bool CopyFolder(const QString& from, const QString& to) {
  QDir().mkpath(to);
  for (const QFileInfo& entry : QDir(from).entryInfoList(QDir::Files | QDir::Dirs | QDir::NoDotAndDotDot)) {
    const QString target = to + "/" + entry.fileName();
    if (entry.isDir() ? !CopyFolder(entry.filePath(), target) : !QFile::copy(entry.filePath(), target)) return false;
  }
  return true;
}

void Settle(int ms) {
  QElapsedTimer timer;
  timer.start();
  while (timer.elapsed() < ms) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(10);
  }
}

std::vector<std::string> FitProblems(QWidget* window) {
  std::vector<std::string> problems;
  const QRect screen = window->screen()->availableGeometry();
  if (!screen.contains(window->frameGeometry()))
    problems.push_back("the window " + RectText(window->frameGeometry()) + " exceeds the screen " + RectText(screen));
  for (const QScrollArea* panel : window->findChildren<QScrollArea*>("panel_scroll")) {
    if (!panel->isVisible() || !panel->widget()) continue;
    const QSize content = panel->widget()->size(), room = panel->viewport()->size();
    if (content.width() > room.width() || content.height() > room.height())
      problems.push_back(Describe(panel->widget()) + " needs " + RectText(QRect(QPoint(), content)) +
                         ", the window gives it " + RectText(QRect(QPoint(), room)));
  }
  for (const QWidget* w : window->findChildren<QWidget*>()) {
    if (!w->isVisible()) continue;
    if (const auto* label = qobject_cast<const QLabel*>(w)) CheckLabel(label, &problems);
    if (!IsControl(w)) continue;
    if (const QWidget* clip = ClippingAncestor(w, window))
      problems.push_back(Describe(w) + " " + RectText(QRect(w->mapTo(window, QPoint(0, 0)), w->size())) +
                         " is clipped by " + Describe(clip));
    if (const auto* table = qobject_cast<const QTableView*>(w)) CheckTableHeight(table, &problems);
    CheckSqueezed(w, &problems);
  }
  return problems;
}

}  // namespace hexcal::ui

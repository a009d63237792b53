#include "ui/panel_scroll.h"

#include <QEvent>
#include <QScrollBar>
#include <QTimer>
#include <algorithm>

namespace hexcal::ui {

PanelScroll::PanelScroll(QWidget* panel, QWidget* parent) : QScrollArea(parent) {
  setObjectName("panel_scroll");
  setFrameShape(QFrame::NoFrame);
  setWidgetResizable(false);  // FitPanel sizes it
  setWidget(panel);
  panel->installEventFilter(this);
}

void PanelScroll::resizeEvent(QResizeEvent* event) {
  QScrollArea::resizeEvent(event);
  FitPanel();
}

// A panel's layout changed (a job's text, a verdict): fit it again once the
// layout has taken the change in.
bool PanelScroll::eventFilter(QObject* watched, QEvent* event) {
  if (watched == widget() && event->type() == QEvent::LayoutRequest)
    QTimer::singleShot(0, this, &PanelScroll::FitPanel);
  return QScrollArea::eventFilter(watched, event);
}

void PanelScroll::FitPanel() {
  QWidget* panel = widget();
  if (panel == nullptr) return;
  const QSize room = maximumViewportSize();  // the viewport without scroll bars
  const QSize least = panel->minimumSizeHint().expandedTo(panel->minimumSize());
  const int width = std::max(room.width(), least.width());
  const int height = std::max(room.height(), least.height());
  // Room for a scroll bar across when the other one shows.
  const int bar = verticalScrollBar()->sizeHint().width();
  const QSize size(height > room.height() && width == room.width() ? width - bar : width, height);
  if (panel->size() != size) panel->resize(size);
}

}  // namespace hexcal::ui

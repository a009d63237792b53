#include "ui/screenshot.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QPixmap>
#include <QThread>
#include <QWidget>

#include "ui/background_job.h"

namespace hexcal::ui {

bool SaveWindowScreenshot(QWidget* window, const QString& file) {
  // Jobs the refresh started (an image's detection) finish first, within reason.
  QElapsedTimer jobs;
  jobs.start();
  const auto busy = [window] {
    for (const BackgroundJob* job : window->findChildren<BackgroundJob*>())
      if (job->Running()) return true;
    return false;
  };
  while (busy() && jobs.elapsed() < 30000) {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(10);
  }
  QElapsedTimer settle;
  settle.start();
  while (settle.elapsed() < 400) {  // layout, chart animation-free repaint, GL first frame
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    QThread::msleep(20);
  }
  return window->grab().save(file, "PNG");
}

}  // namespace hexcal::ui

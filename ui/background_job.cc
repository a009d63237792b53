#include "ui/background_job.h"

#include <QProgressBar>
#include <QThread>
#include <exception>
#include <memory>

#include "ui/error_dialog.h"

namespace hexcal::ui {

BackgroundJob::BackgroundJob(QObject* parent) : QObject(parent) {}

BackgroundJob::~BackgroundJob() {
  if (thread_) {
    cancel_ = true;
    thread_->wait();
    delete thread_;
  }
}

bool BackgroundJob::Start(const QString& what, JobWork work) {
  if (thread_) return false;
  cancel_ = false;
  abandoned_ = false;
  what_ = what;
  // The continuation is made on the worker and run on the GUI thread; a
  // shared_ptr hands it over without copying the result twice.
  auto continuation = std::make_shared<GuiContinuation>();
  JobContext context{[this, what](int done, int total) { emit Progress(done, total, what); }, &cancel_};
  thread_ = QThread::create([work = std::move(work), context, continuation] {
    try {
      *continuation = work(context);
    } catch (const std::exception& e) {
      // Core code reports errors as Status; an exception here is a bug, but
      // the operator gets a dialog, not a dead workstation.
      const QString message = QString::fromStdString(e.what());
      *continuation = [message] { ShowError(nullptr, "Internal error", message + "\nPlease report this."); };
    }
  });
  connect(thread_, &QThread::finished, this, [this, continuation] {
    thread_->deleteLater();
    thread_ = nullptr;
    if (*continuation && !abandoned_) (*continuation)();
    emit Finished();
  });
  emit Started(what);
  thread_->start();
  return true;
}

void BackgroundJob::Cancel() { cancel_ = true; }

void ShowProgressOn(BackgroundJob* job, QProgressBar* bar) {
  // Shown while a job reports progress, hidden after: a full bar left behind
  // says "done" about a job long over, and takes a row a small screen needs.
  bar->setVisible(false);
  QObject::connect(job, &BackgroundJob::Progress, bar, [bar](int done, int total, const QString& what) {
    bar->setFormat(what + " %v/%m");
    bar->setRange(0, total);
    bar->setValue(done);
    bar->setVisible(true);
  });
  QObject::connect(job, &BackgroundJob::Finished, bar, [bar] { bar->setVisible(false); });
}

void BackgroundJob::Abandon() {
  if (!thread_) return;
  cancel_ = true;
  abandoned_ = true;
}

}  // namespace hexcal::ui

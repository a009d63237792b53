// One long job at a time, on a worker thread, for one panel.
//
// The work function runs on the worker; it gets the cancel flag and a
// progress reporter as JobHooks (hand them to the core function: PlanPoses,
// MeasureImages, ...).
// It must not touch widgets: it computes a value and returns a closure that
// applies that value, and the closure runs on the GUI thread when the work is
// done. Progress reaches the GUI thread as a queued signal.
//
//   job_->Start("planning", [options](const JobContext& context) {
//     PlanResult result = ...;  // worker thread
//     return [this, result] { ShowPlan(result); };  // GUI thread
//   });
#pragma once

#include <QObject>
#include <QString>
#include <atomic>
#include <functional>

#include "core/job_hooks.h"

class QProgressBar;
class QThread;

namespace hexcal::ui {

// The job's hooks: hand them as they are to the core and vision functions.
// Both are always set: cancel is the Cancel button's flag, progress is
// thread-safe (a queued signal).
using JobContext = JobHooks;

using GuiContinuation = std::function<void()>;
using JobWork = std::function<GuiContinuation(const JobContext&)>;

class BackgroundJob : public QObject {
  Q_OBJECT
 public:
  explicit BackgroundJob(QObject* parent = nullptr);
  // Cancels the job and waits for the worker: a job never outlives its panel.
  ~BackgroundJob() override;

  bool Running() const { return thread_ != nullptr; }
  // What the running (or last) job was started as ("live", "capturing").
  const QString& What() const { return what_; }
  // False if a job is already running.
  bool Start(const QString& what, JobWork work);
  void Cancel();
  // Cancels the job and drops what it would show: its continuation is not
  // run (the session it worked on is no longer open). Finished still comes.
  void Abandon();
  bool CancelRequested() const { return cancel_.load(); }
  bool Abandoned() const { return abandoned_; }

 signals:
  void Progress(int done, int total, const QString& what);
  void Started(const QString& what);
  void Finished();  // after the continuation ran

 private:
  QThread* thread_ = nullptr;
  std::atomic<bool> cancel_{false};
  bool abandoned_ = false;
  QString what_;
};

// The job's progress on `bar`: "measuring 3/16", a busy bar while the total is 0;
// the bar is shown only while a job reports progress.
void ShowProgressOn(BackgroundJob* job, QProgressBar* bar);

}  // namespace hexcal::ui

// JobHooks: how a caller follows and stops a long job (planning, measuring,
// calibrating, a study). One type across core, vision and workflow; the CLI
// turns it into progress bars, the GUI into a progress bar and Cancel.
//
//   std::atomic<bool> cancel{false};
//   JobHooks hooks{[&](int done, int total) { bar.Update(done, total); }, &cancel};
//   StatusOr<X> x = LongJob(..., hooks);  // Status::Cancelled once `cancel` is raised
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <utility>

namespace hexcal {

struct JobHooks {
  JobHooks() = default;
  JobHooks(std::function<void(int, int)> progress_callback,  // NOLINT: implicit, as a plain callback
           const std::atomic<bool>* cancel_flag = nullptr)
      : progress(std::move(progress_callback)), cancel(cancel_flag) {}

  std::function<void(int done, int total)> progress;  // may be empty
  const std::atomic<bool>* cancel = nullptr;          // raised by the caller to stop the job
  std::function<void(const std::string& stage)> stage;  // the job starts a new stage (may be empty)
  std::function<void(const std::string& line)> note;    // a line for the user's log (may be empty)

  bool Cancelled() const { return cancel != nullptr && cancel->load(); }
  void Progress(int done, int total) const {
    if (progress) progress(done, total);
  }
  void Stage(const std::string& name) const {
    if (stage) stage(name);
  }
  void Note(const std::string& line) const {
    if (note) note(line);
  }
};

}  // namespace hexcal

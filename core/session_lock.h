// One writer per session folder (issue 13): an advisory lock, flock(2) on
// DIR/.hexcal.lock, taken by every command and by the GUI while it writes.
//
//   StatusOr<SessionLock> lock = SessionLock::Acquire("run1", LockWait::kNo);
//   if (!lock.ok()) return lock.status();  // "run1: session in use by PID 4242 (hexcal calibrate --session run1); ..."
//   ... read, compute, write ...            // released when `lock` goes out of scope
//
// The kernel drops a flock when its holder dies, however it dies (kill -9, a
// crash, power loss on a local disk): a lock left by a killed process is free
// at once; its PID line is overwritten by the next holder. Within a process
// the lock is re-entrant on the thread that holds it (a step calling another
// step); another thread of the same process waits like another process.
// Sessions live on a local file system: on NFS flock is emulated with POSIX
// locks, which closing any descriptor of the file drops.
// docs/session.md, "One writer at a time".
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "core/status.h"

namespace hexcal {

enum class LockWait {
  kNo,       // stop at once with "session in use by PID n (command)": a Status of kind kBusy
  kBriefly,  // wait up to kBriefLockWait, then stop the same way (the GUI's edits)
  kForever,  // wait until the holder is done (`--wait`)
};
constexpr std::chrono::seconds kBriefLockWait{3};

class SessionLock {
 public:
  static StatusOr<SessionLock> Acquire(const std::string& session_dir, LockWait wait);

  SessionLock(SessionLock&&) noexcept;
  SessionLock& operator=(SessionLock&&) noexcept;
  SessionLock(const SessionLock&) = delete;
  SessionLock& operator=(const SessionLock&) = delete;
  ~SessionLock();

  struct Held;  // the process-wide record of one locked folder

 private:
  explicit SessionLock(std::shared_ptr<Held> held) : held_(std::move(held)) {}
  std::shared_ptr<Held> held_;
};

// The lock file's path, DIR/.hexcal.lock.
std::string SessionLockPath(const std::string& session_dir);

// "PID 4242 (hexcal calibrate --session run1)": who holds the session's lock
// now, from the lock file, or "" when nobody does.
std::string SessionLockHolder(const std::string& session_dir);

}  // namespace hexcal

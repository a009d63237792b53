#include "core/session_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include "core/atomic_file.h"

namespace hexcal {
namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxHolderChars = 160;
constexpr std::chrono::milliseconds kPollInterval{100};

// The folders this process has locked, by canonical path: a thread that locks
// a folder it already holds shares the hold (re-entrant).
std::mutex registry_mutex;
std::map<std::string, std::weak_ptr<SessionLock::Held>>& Registry() {
  static auto* registry = new std::map<std::string, std::weak_ptr<SessionLock::Held>>;
  return *registry;
}

// Printable ASCII only, at most kMaxHolderChars: the holder line is shown in
// error messages and the GUI, and the lock file may hold anything.
std::string Printable(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (out.size() >= kMaxHolderChars) break;
    out.push_back(c >= 0x20 && c < 0x7f ? c : '?');
  }
  return out;
}

// "hexcal calibrate --session run1", from /proc/self/cmdline.
std::string ThisCommand() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string command;
  size_t start = 0;
  for (size_t end; start < all.size() && command.size() < kMaxHolderChars; start = end + 1) {
    end = all.find('\0', start);
    if (end == std::string::npos) end = all.size();
    std::string word = all.substr(start, end - start);
    if (command.empty()) word = fs::path(word).filename().string();
    command += (command.empty() ? "" : " ") + word;
  }
  return Printable(command.empty() ? "unknown command" : command);
}

std::string ReadHolderLine(int fd) {
  char text[kMaxHolderChars + 1] = {};
  const ssize_t got = ::pread(fd, text, kMaxHolderChars, 0);
  std::string line = got > 0 ? std::string(text, static_cast<size_t>(got)) : "";
  if (const size_t end = line.find('\n'); end != std::string::npos) line.resize(end);
  return Printable(line);
}

StatusOr<int> OpenLockFile(const std::string& path) {
  // O_NOFOLLOW: a lock file that is a symlink is refused, never followed.
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0666);
  // A lock file someone else made, or a read-only folder: flock works on a
  // read-only descriptor too (the PID line is then not written).
  if (fd < 0 && (errno == EACCES || errno == EROFS)) fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return FileSystemError(path, "cannot open the session lock", errno);
  struct stat info;
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd);
    return Status::BadInput(path + ": not a regular file");
  }
  return fd;
}

Status BusyError(const std::string& dir, const std::string& holder) {
  return Status::Busy(dir + ": session in use by " + (holder.empty() ? "another program" : holder) +
                      "; try again when it has finished (the command line's --wait waits for it)");
}

}  // namespace

struct SessionLock::Held {
  int fd = -1;
  std::thread::id owner;
  std::string key;
  ~Held() {
    {
      std::lock_guard<std::mutex> guard(registry_mutex);
      Registry().erase(key);
    }
    // Clear the PID line first: a reader then never names a finished holder.
    if (::ftruncate(fd, 0) != 0) { /* the lock is dropped below all the same */ }
    ::flock(fd, LOCK_UN);
    ::close(fd);
  }
};

std::string SessionLockPath(const std::string& session_dir) { return (fs::path(session_dir) / ".hexcal.lock").string(); }

namespace {

// One attempt: the shared hold of this thread, a new hold, or nothing (busy).
StatusOr<std::shared_ptr<SessionLock::Held>> TryLock(const std::string& dir, const std::string& key, bool* busy) {
  *busy = false;
  std::lock_guard<std::mutex> guard(registry_mutex);
  if (auto found = Registry().find(key); found != Registry().end()) {
    if (std::shared_ptr<SessionLock::Held> held = found->second.lock()) {
      if (held->owner == std::this_thread::get_id()) return held;
      *busy = true;  // another thread of this process writes the session
      return std::shared_ptr<SessionLock::Held>();
    }
  }
  StatusOr<int> fd = OpenLockFile(SessionLockPath(dir));
  if (!fd.ok()) return fd.status();
  if (::flock(*fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(*fd);
    if (error == EWOULDBLOCK || error == EINTR) {
      *busy = true;
      return std::shared_ptr<SessionLock::Held>();
    }
    return Status::IoError(SessionLockPath(dir) + ": cannot lock: " + std::strerror(error));
  }
  auto held = std::make_shared<SessionLock::Held>();
  held->fd = *fd;
  held->owner = std::this_thread::get_id();
  held->key = key;
  const std::string line = "PID " + std::to_string(::getpid()) + " (" + ThisCommand() + ")\n";
  if (::ftruncate(*fd, 0) != 0 || ::pwrite(*fd, line.data(), line.size(), 0) < 0) {
    // The lock holds without its PID line; others then say "another program".
  }
  Registry()[key] = held;
  return held;
}

}  // namespace

StatusOr<SessionLock> SessionLock::Acquire(const std::string& session_dir, LockWait wait) {
  std::error_code error;
  if (!fs::is_directory(session_dir, error)) return Status::BadInput(session_dir + ": not a session folder");
  const std::string key = fs::weakly_canonical(session_dir, error).string();
  const auto deadline = std::chrono::steady_clock::now() + kBriefLockWait;
  for (;;) {
    bool busy = false;
    StatusOr<std::shared_ptr<Held>> held = TryLock(session_dir, key, &busy);
    if (!held.ok()) return held.status();
    if (!busy) return SessionLock(*held);
    const bool give_up = wait == LockWait::kNo || (wait == LockWait::kBriefly && std::chrono::steady_clock::now() > deadline);
    if (give_up) return BusyError(session_dir, SessionLockHolder(session_dir));
    std::this_thread::sleep_for(kPollInterval);
  }
}

SessionLock::SessionLock(SessionLock&&) noexcept = default;
SessionLock& SessionLock::operator=(SessionLock&&) noexcept = default;
SessionLock::~SessionLock() = default;

std::string SessionLockHolder(const std::string& session_dir) {
  const int fd = ::open(SessionLockPath(session_dir).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return "";
  struct stat info;
  std::string holder;
  // A shared lock that can be taken means no writer holds the session.
  if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && ::flock(fd, LOCK_SH | LOCK_NB) != 0) {
    holder = ReadHolderLine(fd);
  }
  ::close(fd);
  return holder;
}

}  // namespace hexcal

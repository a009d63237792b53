#include "core/session_lock.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <thread>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

// A child process that takes the lock and then waits to be killed; returns
// its PID once it holds the lock.
pid_t ChildHoldingTheLock(const std::string& dir) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t child = ::fork();
  if (child == 0) {
    StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kNo);
    const char byte = lock.ok() ? 'y' : 'n';
    if (::write(ready[1], &byte, 1) != 1) ::_exit(2);
    for (;;) ::pause();
  }
  char byte = 0;
  if (::read(ready[0], &byte, 1) != 1 || byte != 'y') return -1;
  ::close(ready[0]);
  ::close(ready[1]);
  return child;
}

void Kill(pid_t child) {
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
}

TEST(SessionLock, ASecondProcessIsRefusedWithTheHoldersPid) {
  TempDir dir;
  const pid_t child = ChildHoldingTheLock(dir.path().string());
  ASSERT_GT(child, 0);
  StatusOr<SessionLock> second = SessionLock::Acquire(dir.path().string(), LockWait::kNo);
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.status().kind(), StatusKind::kBusy);
  EXPECT_NE(second.status().message().find("session in use by PID " + std::to_string(child) + " ("),
            std::string::npos)
      << second.status().message();
  EXPECT_EQ(SessionLockHolder(dir.path().string()).rfind("PID " + std::to_string(child), 0), 0u);
  Kill(child);
}

TEST(SessionLock, ALockLeftByAKilledProcessIsFreeAtOnce) {
  TempDir dir;
  const pid_t child = ChildHoldingTheLock(dir.path().string());
  ASSERT_GT(child, 0);
  Kill(child);
  EXPECT_EQ(SessionLockHolder(dir.path().string()), "");  // its PID line is stale, and not reported
  StatusOr<SessionLock> next = SessionLock::Acquire(dir.path().string(), LockWait::kNo);
  EXPECT_TRUE(next.ok()) << next.status().message();
}

TEST(SessionLock, WaitingTakesTheLockWhenTheHolderDies) {
  TempDir dir;
  const pid_t child = ChildHoldingTheLock(dir.path().string());
  ASSERT_GT(child, 0);
  std::thread killer([child] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    Kill(child);
  });
  StatusOr<SessionLock> waited = SessionLock::Acquire(dir.path().string(), LockWait::kForever);
  killer.join();
  EXPECT_TRUE(waited.ok()) << waited.status().message();
}

TEST(SessionLock, IsReentrantOnItsThreadAndExcludesOtherThreads) {
  TempDir dir;
  const std::string path = dir.path().string();
  StatusOr<SessionLock> outer = SessionLock::Acquire(path, LockWait::kNo);
  ASSERT_TRUE(outer.ok());
  {
    StatusOr<SessionLock> inner = SessionLock::Acquire(path, LockWait::kNo);  // a step calling a step
    EXPECT_TRUE(inner.ok()) << inner.status().message();
  }
  std::future<StatusOr<SessionLock>> other =
      std::async(std::launch::async, [&] { return SessionLock::Acquire(path, LockWait::kNo); });
  EXPECT_EQ(other.get().status().kind(), StatusKind::kBusy);  // the inner release kept the outer hold
  outer = Status::BadInput("released");
  std::future<StatusOr<SessionLock>> after =
      std::async(std::launch::async, [&] { return SessionLock::Acquire(path, LockWait::kNo); });
  EXPECT_TRUE(after.get().ok());
  EXPECT_EQ(SessionLockHolder(path), "");
}

TEST(SessionLock, RefusesALockFileThatIsASymlinkAndAMissingFolder) {
  TempDir dir;
  std::filesystem::create_symlink(dir.File("elsewhere"), SessionLockPath(dir.path().string()));
  EXPECT_FALSE(SessionLock::Acquire(dir.path().string(), LockWait::kNo).ok());
  EXPECT_FALSE(std::filesystem::exists(dir.File("elsewhere")));
  EXPECT_FALSE(SessionLock::Acquire(dir.File("missing"), LockWait::kNo).ok());
}

}  // namespace
}  // namespace hexcal

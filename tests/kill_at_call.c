/* kill_at_call.so: an LD_PRELOAD shim that kills its process with SIGKILL
 * just before its Nth call that changes the file system (tests/cli/kill_writes.sh).
 *
 *   HEXCAL_KILL_AT=N   die before the Nth such call (1-based); unset or 0: count only
 *   HEXCAL_KILL_LOG=F  append one line per call ("N name path") to F
 *
 * The calls are the steps a crash-safe write is made of: mkstemp (the temp
 * file), fsync, rename/renameat/renameat2, unlink/unlinkat/remove, mkdir,
 * mkdtemp, rmdir, ftruncate. The write(2) calls into a temp file are not
 * counted: a kill among them leaves only the unpublished temp file, the same
 * state as a kill before its fsync. Killing before each counted call in turn,
 * run after run, puts a kill -9 at every step of every write a command makes. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>

static long calls;

static void Step(const char* name, const char* path) {
  static long kill_at = -1;
  if (kill_at < 0) {
    const char* text = getenv("HEXCAL_KILL_AT");
    kill_at = text ? atol(text) : 0;
  }
  const long n = __atomic_add_fetch(&calls, 1, __ATOMIC_SEQ_CST);
  const char* log = getenv("HEXCAL_KILL_LOG");
  if (log) {
    char line[512];
    const int length = snprintf(line, sizeof line, "%ld %s %s\n", n, name, path ? path : "-");
    const int fd = (int)syscall(SYS_openat, AT_FDCWD, log, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd >= 0) {
      if (syscall(SYS_write, fd, line, length > 0 ? (size_t)length : 0) < 0) {}
      syscall(SYS_close, fd);
    }
  }
  if (kill_at > 0 && n == kill_at) raise(SIGKILL);
}

/* dlsym returns a void*; ISO C has no cast from it to a function pointer, so
 * the pointer's bytes are copied (what POSIX guarantees to work). */
#define REAL(name)                                      \
  static __typeof__(name)* real_##name;                 \
  if (!real_##name) {                                   \
    void* symbol = dlsym(RTLD_NEXT, #name);             \
    memcpy(&real_##name, &symbol, sizeof symbol);       \
  }

int rename(const char* from, const char* to) { REAL(rename); Step("rename", to); return real_rename(from, to); }
int renameat(int a, const char* from, int b, const char* to) {
  REAL(renameat); Step("renameat", to); return real_renameat(a, from, b, to);
}
int renameat2(int a, const char* from, int b, const char* to, unsigned flags) {
  REAL(renameat2); Step("renameat2", to); return real_renameat2(a, from, b, to, flags);
}
int unlink(const char* path) { REAL(unlink); Step("unlink", path); return real_unlink(path); }
int unlinkat(int dir, const char* path, int flags) {
  REAL(unlinkat); Step("unlinkat", path); return real_unlinkat(dir, path, flags);
}
int remove(const char* path) { REAL(remove); Step("remove", path); return real_remove(path); }
int rmdir(const char* path) { REAL(rmdir); Step("rmdir", path); return real_rmdir(path); }
int mkdir(const char* path, mode_t mode) { REAL(mkdir); Step("mkdir", path); return real_mkdir(path, mode); }
char* mkdtemp(char* pattern) { REAL(mkdtemp); Step("mkdtemp", pattern); return real_mkdtemp(pattern); }
int mkstemp(char* pattern) { REAL(mkstemp); Step("mkstemp", pattern); return real_mkstemp(pattern); }
int fsync(int fd) { REAL(fsync); Step("fsync", NULL); return real_fsync(fd); }
int ftruncate(int fd, off_t length) { REAL(ftruncate); Step("ftruncate", NULL); return real_ftruncate(fd, length); }

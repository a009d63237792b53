#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

namespace hexcal {
namespace {

// The umask cannot be read without setting it (umask(2)), which would race with
// other threads creating files; Linux publishes it in /proc/self/status.
mode_t ProcessUmask() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Umask:", 0) == 0) {
      return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
    }
  }
  return 022;
}

// mkstemp creates 0600 files; a replaced file keeps its mode, a new one gets
// what open(2) would have given it.
mode_t ModeForTarget(const std::string& path) {
  struct stat existing;
  if (::stat(path.c_str(), &existing) == 0) return existing.st_mode & 07777;
  return 0666 & ~ProcessUmask();
}

bool WriteAll(int fd, const std::string& contents) {
  const char* data = contents.data();
  size_t remaining = contents.size();
  while (remaining > 0) {
    const ssize_t written = ::write(fd, data, remaining);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    remaining -= static_cast<size_t>(written);
  }
  return true;
}

// Makes the rename itself durable. Some file systems cannot sync a directory
// and say so with EINVAL; the data is still written, so that is not a failure.
Status SyncDirectory(const std::string& path, const std::string& dir) {
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) return FileSystemError(path, "cannot open folder '" + dir + "' to sync it", errno);
  const int result = ::fsync(dir_fd);
  const int sync_errno = errno;
  ::close(dir_fd);
  if (result != 0 && sync_errno != EINVAL) {
    return FileSystemError(path, "cannot sync folder '" + dir + "'", sync_errno);
  }
  return Status::Ok();
}

// A writer killed inside WriteFileAtomically leaves its temp file behind. The
// next successful write of the same target removes those older than
// kStaleTempAge: a live writer's temp file is seconds old at most (hexcal's
// files are small), so one this old belongs to a dead process.
void RemoveStaleTempFiles(const std::string& dir, const std::string& basename) {
  namespace fs = std::filesystem;
  const std::string prefix = "." + basename + ".tmp.";
  const size_t mkstemp_suffix = 6;  // the XXXXXX
  std::error_code error;
  const fs::file_time_type cutoff = fs::file_time_type::clock::now() - kStaleTempAge;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + mkstemp_suffix || name.compare(0, prefix.size(), prefix) != 0) continue;
    std::error_code entry_error;
    if (!entry.is_regular_file(entry_error) || entry.last_write_time(entry_error) > cutoff || entry_error) continue;
    fs::remove(entry.path(), entry_error);  // best effort: the write itself has succeeded
  }
}

const char* FileTypeName(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

std::string MiBText(size_t bytes) {
  const double mib = static_cast<double>(bytes) / static_cast<double>(kMiB);
  char text[32];
  std::snprintf(text, sizeof(text), mib < 10 ? "%.1f MiB" : "%.0f MiB", mib);
  return text;
}

Status TooLarge(const std::string& path, size_t bytes, size_t max_bytes) {
  return Status::BadInput(path + ": " + MiBText(bytes) + " is over the " + MiBText(max_bytes) +
                          " limit for this kind of file");
}

Status CheckReadableFile(const std::string& path, const struct stat& info, size_t max_bytes) {
  if (S_ISDIR(info.st_mode)) return Status::BadInput(path + ": is a directory, not a file");
  if (!S_ISREG(info.st_mode)) {
    return Status::BadInput(path + ": not a regular file (" + FileTypeName(info.st_mode) + ")");
  }
  if (static_cast<uint64_t>(info.st_size) > max_bytes) {
    return TooLarge(path, static_cast<size_t>(info.st_size), max_bytes);
  }
  return Status::Ok();
}

// open(2) failed: a dangling link says "no such file" in errno's words, yet
// the name is there (ls shows it), so it gets its own message.
Status OpenError(const std::string& path, int error_number) {
  struct stat link;
  if (error_number == ENOENT && ::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
    return Status::BadInput(path + ": a symbolic link to a missing file");
  if (error_number == ENOENT) return Status::BadInput(path + ": no such file");
  if (error_number == ELOOP) return Status::BadInput(path + ": a loop of symbolic links");
  return FileSystemError(path, "cannot open", error_number);
}

// Reads to the end, but never more than max_bytes: the file may grow while read.
StatusOr<std::string> ReadAll(int fd, const std::string& path, size_t max_bytes) {
  std::string contents;
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0) {
      if (errno == EINTR) continue;
      return FileSystemError(path, "read failed", errno);
    }
    if (n == 0) return contents;
    contents.append(buffer, static_cast<size_t>(n));
    if (contents.size() > max_bytes) return TooLarge(path, contents.size(), max_bytes);
  }
}

}  // namespace

Status WriteFileAtomically(const std::string& path, const std::string& contents) {
  const std::filesystem::path target(path);
  const std::string basename = target.filename().string();
  if (basename.empty() || basename == "." || basename == "..") {
    return Status::BadInput(path + ": not a file name");
  }
  const std::string dir = target.has_parent_path() ? target.parent_path().string() : ".";
  std::string temp_path = dir + "/." + basename + ".tmp.XXXXXX";
  std::vector<char> temp_name(temp_path.begin(), temp_path.end());
  temp_name.push_back('\0');

  const int fd = ::mkstemp(temp_name.data());
  if (fd < 0) return FileSystemError(path, "cannot create a temporary file in '" + dir + "'", errno);
  temp_path = temp_name.data();

  // Every failure below removes the temp file and reports the first error.
  auto fail = [&](const std::string& what, int error_number, bool close_fd) {
    if (close_fd) ::close(fd);
    ::unlink(temp_path.c_str());
    return FileSystemError(path, what, error_number);
  };
  if (::fchmod(fd, ModeForTarget(path)) != 0) return fail("cannot set permissions", errno, true);
  if (!WriteAll(fd, contents)) return fail("write failed", errno, true);
  if (::fsync(fd) != 0) return fail("fsync failed", errno, true);
  if (::close(fd) != 0) return fail("close failed", errno, false);
  if (::rename(temp_path.c_str(), path.c_str()) != 0) {
    return fail("cannot rename the temporary file over it", errno, false);
  }
  RemoveStaleTempFiles(dir, basename);
  return SyncDirectory(path, dir);
}

Status CreateFolders(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return Status::Ok();
  std::filesystem::create_directories(path, error);
  if (!error && std::filesystem::is_directory(path, error)) return Status::Ok();
  if (!error) return Status::BadInput(path + ": cannot create the folder: a file of that name is in the way");
  return FileSystemError(path, "cannot create the folder", error.value());
}

Status FileSystemError(const std::string& path, const std::string& what, int error_number) {
  const std::string message = path + ": " + what + ": " + std::strerror(error_number);
  switch (error_number) {
    case ENOENT:
    case ENOTDIR:
    case EISDIR:
    case ENAMETOOLONG:
    case ELOOP:
    case EEXIST:
      return Status::BadInput(message);
    default:
      return Status::IoError(message);
  }
}

Status CheckOutputFree(const std::string& path, bool force) {
  struct stat info;
  // stat follows links: the rename would replace a link to /dev/sda or to a
  // pipe (/dev/stdout) with a file, which is no more what was meant.
  if (path.empty() || ::stat(path.c_str(), &info) != 0) return Status::Ok();
  if (S_ISDIR(info.st_mode)) return Status::BadInput(path + ": is a directory, not a file");
  // --force or not: the rename would put a file where a device node, a FIFO
  // or a socket was (as root, over /dev/null too).
  if (!S_ISREG(info.st_mode)) {
    return Status::BadInput(path + ": not a regular file (" + FileTypeName(info.st_mode) +
                            "); hexcal replaces only files");
  }
  if (force) return Status::Ok();
  return Status::BadInput(path + ": exists; use --force to overwrite it");
}

StatusOr<int> OpenFileForReading(const std::string& path, size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat of the opened
  // descriptor (not stat of the path) so that a swapped file cannot slip by.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return OpenError(path, errno);
  struct stat info;
  if (::fstat(fd, &info) != 0) {
    const int stat_errno = errno;
    ::close(fd);
    return FileSystemError(path, "cannot access", stat_errno);
  }
  if (Status s = CheckReadableFile(path, info, max_bytes); !s.ok()) {
    ::close(fd);
    return s;
  }
  return fd;
}

Status CheckFileForReading(const std::string& path, size_t max_bytes) {
  StatusOr<int> fd = OpenFileForReading(path, max_bytes);
  if (!fd.ok()) return fd.status();
  ::close(*fd);
  return Status::Ok();
}

StatusOr<std::string> ReadFileToString(const std::string& path, size_t max_bytes) {
  StatusOr<int> fd = OpenFileForReading(path, max_bytes);
  if (!fd.ok()) return fd.status();
  StatusOr<std::string> contents = ReadAll(*fd, path, max_bytes);
  ::close(*fd);
  return contents;
}

}  // namespace hexcal

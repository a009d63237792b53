#include "core/staged_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/atomic_file.h"

namespace hexcal {
namespace {

namespace fs = std::filesystem;

std::string StagingPrefix(const fs::path& final_path) { return "." + final_path.filename().string() + ".new-"; }

// Folders PARENT/.NAME.new-* left by writers that were killed before they
// published or before they removed the folder they swapped out.
void RemoveStaleStaging(const fs::path& final_path) {
  const std::string prefix = StagingPrefix(final_path);
  std::error_code error;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(final_path.parent_path(), error), end; !error && it != end; it.increment(error)) {
    if (it->path().filename().string().rfind(prefix, 0) == 0) stale.push_back(it->path());
  }
  for (const fs::path& folder : stale) fs::remove_all(folder, error);  // a symlink is removed, not followed
}

void SyncFolder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

StatusOr<StagedFolder> StagedFolder::Begin(const std::string& final_path) {
  const fs::path target = fs::path(final_path).lexically_normal();
  fs::path parent = target.parent_path();
  if (parent.empty()) parent = ".";
  std::error_code error;
  if (!fs::is_directory(parent, error)) return Status::BadInput(parent.string() + ": no such folder");
  RemoveStaleStaging(fs::path(parent) / target.filename());
  std::string pattern = (parent / (StagingPrefix(target) + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    return FileSystemError(parent.string(), "cannot create a folder", errno);
  }
  // mkdtemp makes 0700; results are readable by all, as a folder made under
  // the usual umask 022 would be.
  ::chmod(pattern.c_str(), 0755);
  return StagedFolder((parent / target.filename()).string(), pattern);
}

StagedFolder::StagedFolder(StagedFolder&& other) noexcept
    : final_(std::move(other.final_)), staging_(std::move(other.staging_)), published_(other.published_) {
  other.published_ = true;  // the moved-from object removes nothing
}

StagedFolder::~StagedFolder() {
  if (published_) return;
  std::error_code error;
  fs::remove_all(staging_, error);
}

std::string StagedFolder::File(const std::string& name) const { return (fs::path(staging_) / name).string(); }

Status StagedFolder::Publish() {
  if (published_) return Status::BadInput(final_ + ": already published");
  SyncFolder(staging_);  // the entries of the new folder are on disk before it is swapped in
  struct stat existing;
  const bool replacing = ::lstat(final_.c_str(), &existing) == 0;
  int renamed = replacing ? ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE)
                          : ::rename(staging_.c_str(), final_.c_str());
  if (renamed != 0 && replacing && (errno == EINVAL || errno == ENOSYS)) {
    // A file system without RENAME_EXCHANGE: move the old folder aside first.
    // A reader in between finds no folder, never a mix.
    const std::string aside = staging_ + ".old";
    renamed = ::rename(final_.c_str(), aside.c_str());
    if (renamed == 0) renamed = ::rename(staging_.c_str(), final_.c_str());
    if (renamed == 0) renamed = ::rename(aside.c_str(), staging_.c_str());
  }
  if (renamed != 0) return Status::IoError(final_ + ": cannot publish the new folder: " + std::strerror(errno));
  published_ = true;
  SyncFolder(fs::path(final_).parent_path().empty() ? fs::path(".") : fs::path(final_).parent_path());
  // The old folder (or link) now sits at the staging name.
  std::error_code error;
  if (replacing) fs::remove_all(staging_, error);
  return Status::Ok();
}

}  // namespace hexcal

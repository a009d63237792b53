#include "workflow/acquire_files.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/session.h"
#include "workflow/session_edits.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// The capture acquire is writing, named in SESSION/.acquire-pending from
// before its image is written until its row is: an image left without its
// row by a kill between RecordCapture's two writes is then known to be
// acquire's (removed and taken again), and any other image without a row an
// operator's own (kept; the pose is refused).
constexpr const char* kPendingCapture = ".acquire-pending";

std::string PendingCapture(const std::string& dir) {
  StatusOr<std::string> text = ReadFileToString((fs::path(dir) / kPendingCapture).string(), 4096);
  if (!text.ok()) return "";
  std::string name = *text;
  while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
  return name;
}

}  // namespace

// The images that have a row in legs.csv. Read as a plain table, not with
// LoadSessionLegs: an image left without its row by a killed capture must not
// stop the run that records it again.
StatusOr<std::set<std::string>> ImagesWithRows(const std::string& dir) {
  const std::string path = SessionPaths(dir).legs;
  std::error_code error;
  if (!fs::exists(path, error)) return std::set<std::string>{};
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return table.status();
  StatusOr<int> column = ColumnIndex(*table, "image");
  if (!column.ok()) return column.status();
  std::set<std::string> images;
  for (const std::vector<std::string>& row : table->rows) images.insert(row[*column]);
  return images;
}

// Whether pose's image may be written: no file there, or the one a killed
// capture of acquire left (removed when `remove`). Never another file.
Status ClearImageSlot(const std::string& dir, const std::string& image, bool remove, const JobHooks& hooks) {
  const fs::path path = fs::path(SessionPaths(dir).images) / image;
  std::error_code error;
  if (!fs::exists(fs::symlink_status(path, error))) return Status::Ok();
  if (PendingCapture(dir) != image)
    return Status::BadInput("images/" + image + " exists without a row in legs.csv and hexcal acquire did not " +
                            "write it: move it away, or record its readings (hexcal session record), then run again");
  if (!remove) return Status::Ok();
  fs::remove(path, error);
  if (error)
    return Status::IoError(path.string() + ": cannot remove an image left without its row: " + error.message());
  hooks.Note("images/" + image + " had no row in legs.csv (an interrupted capture): recording it again");
  return Status::Ok();
}

// The image and its row (RecordCaptureBytes), with the pending name around them.
Status RecordWithPendingName(const std::string& dir, const std::string& png, const LegsRow& row, LockWait wait) {
  const std::string pending = (fs::path(dir) / kPendingCapture).string();
  if (Status s = WriteFileAtomically(pending, row.image + "\n"); !s.ok()) return s;
  const EditOutcome outcome = RecordCaptureBytes(dir, png, row, {false, wait});
  if (!outcome.status.ok()) return outcome.status;
  if (outcome.conflict) return Status::BadInput(outcome.conflict_text);
  std::error_code error;
  fs::remove(pending, error);  // a name left behind names an image with its row: harmless
  return Status::Ok();
}

// What a run needs of the session, checked before a machine is powered on
// and homed (issue 33): legs.csv parses and images/ takes a new file (a file
// made and removed there: permission bits say nothing to root, a read-only
// mount or a full disk does). Sorted by FileSystemError: a file standing
// where images/ should be is the session's fault (bad input), a disk that
// refuses an I/O error.
Status CheckSessionTakesCaptures(const std::string& dir) {
  StatusOr<std::set<std::string>> recorded = ImagesWithRows(dir);
  if (!recorded.ok()) return recorded.status();
  const std::string images = SessionPaths(dir).images;
  std::error_code error;
  fs::create_directories(images, error);
  std::string probe = (fs::path(images) / ".hexcal-acquire-XXXXXX").string();
  const int fd = error ? -1 : mkstemp(probe.data());
  if (fd < 0)
    return FileSystemError(images, "cannot write a new file there (nothing was moved)", error ? error.value() : errno);
  close(fd);
  fs::remove(probe, error);
  return Status::Ok();
}

}  // namespace hexcal::workflow

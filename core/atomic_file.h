// Whole-file reads and crash-safe writes for every file hexcal produces.
//
// A plan, a measurement table or a calibrated robot file is written to a
// temporary file in the target's folder and renamed over the target, so a
// reader (or a crash, or a full disk) never sees half a file: the target holds
// either its old contents or the new ones.
//
//   Status written = WriteFileAtomically("robot.calibrated.yaml", yaml_text);
//   StatusOr<std::string> text = ReadFileToString("plan.csv");
//   if (!text.ok()) std::cerr << text.status().message() << "\n";
//
// Error messages begin with the path, e.g. "plan.csv: no such file".
#pragma once

#include <chrono>
#include <string>

#include "core/status.h"

namespace hexcal {

// Writes `contents` to `path` via a temp file `.<basename>.tmp.XXXXXX` in the
// same folder, fsync, rename and fsync of the folder. An existing target keeps
// its permissions; a new file gets 0666 minus the process umask. On failure the
// temp file is removed and the target is left untouched.
// A successful write also removes the target's temp files older than
// kStaleTempAge, left by writers that were killed (kill -9, power loss).
Status WriteFileAtomically(const std::string& path, const std::string& contents);
constexpr std::chrono::minutes kStaleTempAge{10};

// Size caps of the files hexcal reads, by kind: far above any real file of
// that kind, far below what would exhaust memory (issue 13, bounded input).
constexpr size_t kMiB = size_t{1} << 20;
constexpr size_t kMaxYamlBytes = 4 * kMiB;     // robot, session, target, camera, plan settings
constexpr size_t kMaxTableBytes = 256 * kMiB;  // CSV tables (poses, legs, measurements)
constexpr size_t kMaxJsonBytes = 64 * kMiB;    // report.json
constexpr size_t kMaxImageBytes = 512 * kMiB;  // PNG, JPEG, TIFF

// Refuses to replace an existing output file unless the user gave --force:
// "PATH: exists; use --force to overwrite it" (bad input), the same in every
// command and workflow step. A folder, a FIFO, a device or a socket at PATH
// (also behind a symlink) is refused even with --force: "PATH: not a regular
// file (a FIFO); hexcal replaces only files". An empty path is free.
Status CheckOutputFree(const std::string& path, bool force);

// Creates the folder `path` and its missing parents, with one message and one
// kind of error in every command (issue 36: exit 1 in some, 2 in others),
// sorted by FileSystemError: a path that cannot be a folder (a file in the
// way, a name too long) is bad input; a system that refuses (no permission,
// a full or read-only disk, an I/O error) is an I/O error.
// "PATH: cannot create the folder: Not a directory".
Status CreateFolders(const std::string& path);

// "PATH: WHAT: strerror" as the tier that errno says (core/status.h): a path
// that names the wrong thing (ENOENT, ENOTDIR, EISDIR, ENAMETOOLONG, ELOOP,
// EEXIST) is bad input, anything else the system refused (EACCES, EROFS,
// ENOSPC, EIO, ...) an I/O error. The one rule for a failed file operation.
Status FileSystemError(const std::string& path, const std::string& what, int error_number);

// The whole file as bytes. Errors: missing file, a dangling symbolic link, a
// directory, not a regular file (a FIFO, a device, a socket: refused at once,
// never waited on, also behind a symlink), larger than `max_bytes`, unreadable.
StatusOr<std::string> ReadFileToString(const std::string& path, size_t max_bytes = kMaxYamlBytes);

// The one check of every file hexcal reads (issue 36): opens `path` without
// blocking (a FIFO with no writer) and refuses what ReadFileToString refuses,
// each with its own message ("PATH: not a regular file (a FIFO)", "PATH: a
// symbolic link to a missing file", "PATH: is a directory, not a file").
// Returns the open descriptor, which the caller closes.
StatusOr<int> OpenFileForReading(const std::string& path, size_t max_bytes);

// OpenFileForReading's checks for a file that another library opens by its
// path (a video for OpenCV, an image listed for a later read).
Status CheckFileForReading(const std::string& path, size_t max_bytes);

}  // namespace hexcal

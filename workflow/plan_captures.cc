#include "workflow/plan_captures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>

#include "core/atomic_file.h"
#include "core/calibration_file.h"
#include "core/csv.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "workflow/session_edits.h"

namespace hexcal::workflow {

namespace {

namespace fs = std::filesystem;

// A row written before legs.csv held commanded poses: pose k's by its name
// and its readings near the nominal IK of the pose.
bool LegacyCaptureOf(const ReadingCheck& check, int pose_index, const Vector6d& pose, const ReadingsRow& row) {
  // A points session's row is named after the pose, without the image's extension.
  if (row.image != AcquiredImageName(pose_index) && row.image != AcquiredPoseName(pose_index)) return false;
  const LegReadings needed = InverseKinematics(check.robot, check.robot.PoseFromVector(pose));
  for (int i = 0; i < kNumLegs; ++i)
    if (!row.legs[i] || !(std::abs(*row.legs[i] - needed[i]) <= TypedTolerance(check, i))) return false;
  return true;
}

std::string ArchiveStamp() { return CurrentUtcTimestamp("%Y%m%dT%H%M%SZ"); }

// A fresh folder SESSION/archive/captures-STAMP[-N].
StatusOr<fs::path> NewArchiveFolder(const std::string& dir) {
  const fs::path archive = fs::path(dir) / "archive";
  const std::string stamp = "captures-" + ArchiveStamp();
  std::error_code error;
  for (int n = 1; n < 100; ++n) {
    const fs::path folder = archive / (n == 1 ? stamp : stamp + "-" + std::to_string(n));
    if (fs::exists(fs::symlink_status(folder, error))) continue;
    if (Status s = CreateFolders((folder / "images").string()); !s.ok()) return s;
    return folder;
  }
  return Status::IoError(archive.string() + ": no free folder name for " + stamp);
}

}  // namespace

std::string AcquiredImageName(int pose_index) {
  char name[32];
  std::snprintf(name, sizeof name, "pose_%04d.png", pose_index);
  return name;
}

bool SameCommandedPose(const Vector6d& a, const Vector6d& b) {
  for (int k = 0; k < 6; ++k)
    if (!(std::abs(a[k] - b[k]) <= 1e-9 * std::max(1.0, std::max(std::abs(a[k]), std::abs(b[k]))))) return false;
  return true;
}

int CaptureOfPose(const ReadingCheck& check, int pose_index, const Vector6d& pose,
                  const std::vector<ReadingsRow>& rows) {
  for (size_t r = 0; r < rows.size(); ++r) {
    const ReadingsRow& row = rows[r];
    if (!row.recorded) continue;
    if (row.commanded ? SameCommandedPose(*row.commanded, pose) : LegacyCaptureOf(check, pose_index, pose, row))
      return static_cast<int>(r);
  }
  return -1;
}

std::vector<int> CapturesOfPlan(const ReadingCheck& check, const std::vector<Vector6d>& plan,
                                const std::vector<ReadingsRow>& rows) {
  std::vector<int> found;
  for (size_t k = 0; k < plan.size(); ++k) found.push_back(CaptureOfPose(check, static_cast<int>(k), plan[k], rows));
  return found;
}

std::string AcquiredPoseName(int pose_index) {
  const std::string image = AcquiredImageName(pose_index);
  return image.substr(0, image.size() - 4);  // without ".png"
}

namespace {

// `stem` + `extension`, else stem_2, stem_3, ... + extension: the first name
// no row of legs.csv has.
std::string FreeName(const std::string& stem, const std::string& extension, const std::vector<ReadingsRow>& rows) {
  std::set<std::string> taken;
  for (const ReadingsRow& row : rows)
    if (row.recorded) taken.insert(row.image);
  if (!taken.count(stem + extension)) return stem + extension;
  for (int n = 2;; ++n) {
    const std::string name = stem + "_" + std::to_string(n) + extension;
    if (!taken.count(name)) return name;
  }
}

}  // namespace

std::string CaptureImageName(int pose_index, const std::vector<ReadingsRow>& rows) {
  return FreeName(AcquiredPoseName(pose_index), ".png", rows);
}

std::string CapturePoseName(int pose_index, const std::vector<ReadingsRow>& rows) {
  return FreeName(AcquiredPoseName(pose_index), "", rows);
}

std::vector<std::string> CapturesLeftByPlan(const ReadingCheck& check, const std::vector<Vector6d>& old_plan,
                                            const std::vector<Vector6d>& new_plan,
                                            const std::vector<ReadingsRow>& rows) {
  const std::vector<int> old_rows = CapturesOfPlan(check, old_plan, rows);
  const std::vector<int> new_rows = CapturesOfPlan(check, new_plan, rows);
  const std::set<int> kept(new_rows.begin(), new_rows.end());
  std::set<std::string> left;
  for (const int row : old_rows)
    if (row >= 0 && !kept.count(row)) left.insert(rows[row].image);
  return {left.begin(), left.end()};
}

const char* CaptureDisposalName(CaptureDisposal disposal) {
  switch (disposal) {
    case CaptureDisposal::kKeep:
      return "keep";
    case CaptureDisposal::kArchive:
      return "archive";
    case CaptureDisposal::kDiscard:
      return "discard";
  }
  return "?";
}

StatusOr<std::string> ArchiveCaptures(const std::string& dir, const std::vector<std::string>& images) {
  if (Status s = CheckWritableInside(dir, "images"); !s.ok()) return s;
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kBriefly);
  if (!lock.ok()) return lock.status();
  const SessionPaths paths(dir);
  StatusOr<CsvTable> table = ReadCsv(paths.legs);
  if (!table.ok()) return table.status();
  StatusOr<int> image_column = ColumnIndex(*table, "image");
  if (!image_column.ok()) return image_column.status();
  const std::set<std::string> moving(images.begin(), images.end());
  std::vector<std::vector<std::string>> archived, kept;
  for (const std::vector<std::string>& row : table->rows)
    (moving.count(row[*image_column]) ? archived : kept).push_back(row);
  StatusOr<fs::path> folder = NewArchiveFolder(dir);
  if (!folder.ok()) return folder.status();
  // The archive's rows first, then the session's without them, then the
  // images: a kill in between leaves images without rows, which the session
  // names (as RemoveCapture does); nothing is lost.
  if (Status s = WriteFileAtomically((*folder / "legs.csv").string(), FormatCsv(table->header, archived)); !s.ok())
    return s;
  if (Status s = WriteFileAtomically(paths.legs, FormatCsv(table->header, kept)); !s.ok()) return s;
  for (const std::string& image : images) {
    const fs::path from = fs::path(paths.images) / image;
    std::error_code error;
    if (!fs::exists(fs::symlink_status(from, error))) continue;
    fs::rename(from, *folder / "images" / image, error);
    if (error)
      return Status::IoError(from.string() + ": cannot move into " + folder->string() + ": " + error.message());
  }
  return folder->string();
}

Status DiscardCaptures(const std::string& dir, const std::vector<std::string>& images) {
  for (const std::string& image : images)
    if (Status s = RemoveCapture(dir, image); !s.ok()) return s;
  return Status::Ok();
}

}  // namespace hexcal::workflow

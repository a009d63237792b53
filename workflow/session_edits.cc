#include "workflow/session_edits.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "session/session_models.h"
#include "workflow/plan_step.h"
#include "workflow/reading_check.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// legs.csv's key column: `image` (camera sessions), `pose` (points sessions).
StatusOr<std::string> KeyColumn(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  return std::string(MeasurementNoun(config->instrument));
}

// What a points session cannot do: it has no images (docs/session.md).
Status RefuseInPointsSession(const std::string& dir, const std::string& what) {
  StatusOr<std::string> key = KeyColumn(dir);
  if (!key.ok()) return key.status();
  if (*key == "pose")
    return Status::BadInput(dir + ": a points session has no images (its poses come from its points file): cannot " +
                            what);
  return Status::Ok();
}

EditOutcome Failed(Status status) { return EditOutcome{std::move(status), false, ""}; }
EditOutcome Conflict(std::string text) { return EditOutcome{Status::Ok(), true, std::move(text)}; }
EditOutcome Done() { return EditOutcome{}; }

// A file name inside images/ that the session lists (PNG, JPEG, TIFF): never
// a path that leads out of the session.
Status CheckImageName(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.find_first_of(std::string("/\0", 2)) != std::string::npos)
    return Status::BadInput(Excerpt(name) + ": not an image file name (a name inside images/, no folders)");
  // legs.csv holds one row a line: a line break in a name split the row and no
  // command could read the file again (issue 36); other control bytes would
  // reach terminals raw.
  const auto control = [](unsigned char c) { return c < 0x20 || c == 0x7f; };
  if (std::any_of(name.begin(), name.end(), control))
    return Status::BadInput(Excerpt(name) + ": a control character in an image name; legs.csv cannot hold it");
  std::string extension = fs::path(name).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* known : {".png", ".jpg", ".jpeg", ".tif", ".tiff"})
    if (extension == known) return Status::Ok();
  return Status::BadInput(Excerpt(name) + ": not a .png, .jpg or .tif name");
}

// A pose of a points session's legs.csv: the name its points file gives it,
// on one line (a line break would split the row).
Status CheckPoseName(const std::string& name) {
  const auto control = [](unsigned char c) { return c < 0x20 || c == 0x7f; };
  if (name.empty() || std::any_of(name.begin(), name.end(), control))
    return Status::BadInput(Excerpt(name) + ": not a pose name (empty, or a control character legs.csv cannot hold)");
  return Status::Ok();
}

// Readings are finite numbers: a NaN written into legs.csv would make every
// later command refuse the file.
Status CheckReadings(const LegsEdit& edit) {
  const bool finite = edit.kind == LegsEdit::Kind::kSetRow
                          ? edit.row.legs.allFinite() && (!edit.row.commanded || edit.row.commanded->allFinite())
                          : std::isfinite(edit.value);
  return finite ? Status::Ok() : Status::BadInput(edit.image + ": a reading is not a finite number");
}

// legs.csv as it is on disk; a missing file is an empty table with the usual
// header. A file that does not parse is never rewritten: its rows would be lost.
// `key` names the rows (KeyColumn).
StatusOr<CsvTable> ReadLegsTable(const std::string& path, const std::string& key) {
  std::error_code error;
  if (!fs::exists(fs::symlink_status(path, error)))
    return CsvTable{path, {key, "L1", "L2", "L3", "L4", "L5", "L6", "holdout"}, {}, {}};
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return table.status().WithHint(" (fix legs.csv before recording more readings)");
  std::vector<std::string> columns = {key};
  for (int i = 1; i <= kNumLegs; ++i) columns.push_back("L" + std::to_string(i));
  for (const std::string& column : columns)
    if (!ColumnIndex(*table, column).ok()) return ColumnIndex(*table, column).status();
  return table;
}

// The column `name`, added to a file without one with `fill` in every row
// (holdout 0; an empty commanded pose).
int ColumnOf(CsvTable* table, const std::string& name, const std::string& fill = "0") {
  const auto found = std::find(table->header.begin(), table->header.end(), name);
  if (found != table->header.end()) return static_cast<int>(found - table->header.begin());
  table->header.push_back(name);
  for (auto& row : table->rows) row.push_back(fill);
  return static_cast<int>(table->header.size()) - 1;
}

int RowOf(const CsvTable& table, const std::string& key, const std::string& image) {
  const int column = static_cast<int>(std::find(table.header.begin(), table.header.end(), key) - table.header.begin());
  for (size_t r = 0; r < table.rows.size(); ++r)
    if (table.rows[r][column] == image) return static_cast<int>(r);
  return -1;
}

std::vector<std::string> RowCells(CsvTable* table, const std::string& key, const LegsRow& row) {
  // Every column first (a holdout column may be added), then the row's size.
  const int image = ColumnOf(table, key), holdout = ColumnOf(table, "holdout");
  int legs[kNumLegs];
  for (int i = 0; i < kNumLegs; ++i) legs[i] = ColumnOf(table, "L" + std::to_string(i + 1));
  // A capture's commanded pose (core/session.h); a file without the columns
  // gets them, empty in its other rows.
  int commanded[6] = {-1, -1, -1, -1, -1, -1};
  if (row.commanded)
    for (int k = 0; k < 6; ++k) commanded[k] = ColumnOf(table, kCommandedColumns[k], "");
  std::vector<std::string> cells(table->header.size(), "");
  cells[image] = row.image;
  for (int i = 0; i < kNumLegs; ++i) cells[legs[i]] = FormatNumber(row.legs[i]);
  cells[holdout] = row.holdout ? "1" : "0";
  if (row.commanded)
    for (int k = 0; k < 6; ++k) cells[commanded[k]] = FormatNumber((*row.commanded)[k]);
  return cells;
}

// The edit on the table in memory; a conflict text when the value the
// operator saw is no longer there, "" when the edit applied.
StatusOr<std::string> EditTable(CsvTable* table, const std::string& key, const LegsEdit& edit, bool overwrite) {
  const int row = RowOf(*table, key, edit.image);
  if (edit.kind == LegsEdit::Kind::kSetRow) {
    if (row >= 0 && !overwrite) return "legs.csv already has readings for " + edit.image + " (written by another program)";
    const std::vector<std::string> cells = RowCells(table, key, edit.row);
    if (row >= 0) {
      table->rows[row] = cells;
    } else {
      table->rows.push_back(cells);
    }
    return std::string();
  }
  if (row < 0) return Status::BadInput("legs.csv: no row for " + edit.image + " (removed by another program?)");
  const bool reading = edit.kind == LegsEdit::Kind::kSetReading;
  const std::string name = reading ? "L" + std::to_string(edit.leg + 1) : "holdout";
  std::string& cell = table->rows[row][ColumnOf(table, name)];
  StatusOr<double> on_disk = cell.empty() && !reading ? StatusOr<double>(0.0) : ParseNumber(cell);
  if (!overwrite && (!on_disk.ok() || *on_disk != edit.seen)) {
    return "legs.csv: " + name + " of " + edit.image + " is " + Excerpt(cell) + " on disk, not " + FormatNumber(edit.seen) +
           " as shown (another program changed it)";
  }
  cell = reading ? FormatNumber(edit.value) : (edit.value != 0 ? "1" : "0");
  return std::string();
}

}  // namespace

LegsEdit LegsEdit::SetReading(const std::string& image, int leg, double seen, double value) {
  LegsEdit edit;
  edit.kind = Kind::kSetReading;
  edit.image = image;
  edit.leg = leg;
  edit.seen = seen;
  edit.value = value;
  return edit;
}

LegsEdit LegsEdit::SetHoldout(const std::string& image, bool seen, bool value) {
  LegsEdit edit;
  edit.kind = Kind::kSetHoldout;
  edit.image = image;
  edit.seen = seen ? 1 : 0;
  edit.value = value ? 1 : 0;
  return edit;
}

LegsEdit LegsEdit::SetRow(const LegsRow& row) {
  LegsEdit edit;
  edit.kind = Kind::kSetRow;
  edit.image = row.image;
  edit.row = row;
  return edit;
}

namespace {

// legs.csv as it is on disk with the edit applied, not yet written; the
// outcome says why not (an error, a conflict) when it cannot be applied.
StatusOr<CsvTable> EditedLegs(const std::string& dir, const LegsEdit& edit, bool overwrite, EditOutcome* outcome) {
  if (edit.kind == LegsEdit::Kind::kSetReading && (edit.leg < 0 || edit.leg >= kNumLegs))
    return Status::BadInput("leg " + std::to_string(edit.leg + 1) + ": legs are 1 to 6");
  StatusOr<std::string> key = KeyColumn(dir);
  if (!key.ok()) return key.status();
  if (Status s = *key == "pose" ? CheckPoseName(edit.image) : CheckImageName(edit.image); !s.ok()) return s;
  if (Status s = CheckReadings(edit); !s.ok()) return s;
  StatusOr<CsvTable> table = ReadLegsTable(SessionPaths(dir).legs, *key);
  if (!table.ok()) return table.status();
  StatusOr<std::string> conflict = EditTable(&*table, *key, edit, overwrite);
  if (!conflict.ok()) return conflict.status();
  if (!conflict->empty()) {
    *outcome = Conflict(*conflict);
    return Status::BadInput(*conflict);
  }
  return table;
}

}  // namespace

EditOutcome ApplyLegsEdit(const std::string& dir, const LegsEdit& edit, const EditOptions& options) {
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, options.wait);
  if (!lock.ok()) return Failed(lock.status());
  EditOutcome outcome;
  StatusOr<CsvTable> table = EditedLegs(dir, edit, options.overwrite, &outcome);
  if (outcome.conflict) return outcome;
  if (!table.ok()) return Failed(table.status());
  return Failed(WriteFileAtomically(SessionPaths(dir).legs, FormatCsv(table->header, table->rows)));
}

Status CheckWritableInside(const std::string& dir, const std::string& folder) {
  std::error_code error;
  const fs::path session = fs::weakly_canonical(dir, error);
  const fs::path target = fs::weakly_canonical(fs::path(dir) / folder, error);
  const auto [end, unused] = std::mismatch(session.begin(), session.end(), target.begin(), target.end());
  if (error || end != session.end())
    return Status::BadInput((fs::path(dir) / folder).string() +
                            ": leads out of the session folder (a symbolic link); " +
                            "hexcal writes only inside it: make " + folder + "/ a real folder");
  return Status::Ok();
}

EditOutcome RecordCapture(const std::string& dir, const std::string& image_file, const LegsRow& row,
                          const EditOptions& options) {
  if (Status s = RefuseInPointsSession(dir, "record an image"); !s.ok()) return Failed(s);
  StatusOr<std::string> bytes = ReadFileToString(image_file, kMaxImageBytes);
  if (!bytes.ok()) return Failed(bytes.status());
  return RecordCaptureBytes(dir, *bytes, row, options);
}

EditOutcome RecordCaptureBytes(const std::string& dir, const std::string& image_bytes, const LegsRow& row,
                               const EditOptions& options) {
  if (Status s = RefuseInPointsSession(dir, "record an image"); !s.ok()) return Failed(s);
  if (Status s = CheckWritableInside(dir, "images"); !s.ok()) return Failed(s);
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, options.wait);
  if (!lock.ok()) return Failed(lock.status());
  // The row is checked before the image is written: a refused row leaves no
  // image without readings behind.
  EditOutcome outcome;
  StatusOr<CsvTable> table = EditedLegs(dir, LegsEdit::SetRow(row), options.overwrite, &outcome);
  if (outcome.conflict) return outcome;
  if (!table.ok()) return Failed(table.status());
  const std::string target = (fs::path(SessionPaths(dir).images) / row.image).string();
  std::error_code error;
  if (fs::exists(fs::symlink_status(target, error)))  // recorded images are never replaced
    return Failed(Status::BadInput(target + ": exists already; record the capture under another name"));
  if (Status s = WriteFileAtomically(target, image_bytes); !s.ok()) return Failed(s);
  return Failed(WriteFileAtomically(SessionPaths(dir).legs, FormatCsv(table->header, table->rows)));
}

namespace {

// The commanded pose of each image in a legs.csv text (core/session.h's
// columns); none for a text without them or that does not parse.
std::map<std::string, Vector6d> CommandedPoses(const std::string& text, const std::string& source) {
  std::map<std::string, Vector6d> poses;
  StatusOr<CsvTable> table = ParseCsv(text, source);
  if (!table.ok() || !ColumnIndex(*table, "image").ok()) return poses;
  const int image = *ColumnIndex(*table, "image");
  std::array<int, 6> columns{};
  for (int k = 0; k < 6; ++k) {
    StatusOr<int> column = ColumnIndex(*table, kCommandedColumns[k]);
    if (!column.ok()) return poses;
    columns[k] = *column;
  }
  for (size_t r = 0; r < table->rows.size(); ++r) {
    StatusOr<std::optional<Vector6d>> pose = CommandedPoseAt(*table, r, columns, "");
    if (pose.ok() && *pose) poses[table->rows[r][image]] = **pose;
  }
  return poses;
}

// The imported rows checked as typed readings (reading_check.h): within the
// stroke, and near the IK of the pose the image was captured at, from the
// imported file's commanded columns or, without them, the session's.
Status CheckImportedReadings(const std::string& dir, const std::string& legs_file, const std::vector<LegsRow>& rows,
                             const std::map<std::string, Vector6d>& session_commanded) {
  StatusOr<ReadingCheck> check = SessionReadingCheck(dir);
  if (!check.ok()) return check.status();
  for (const LegsRow& row : rows) {
    std::optional<Vector6d> commanded = row.commanded;
    if (const auto found = session_commanded.find(row.image); !commanded && found != session_commanded.end())
      commanded = found->second;
    const std::string where = legs_file + ":" + std::to_string(row.line) + ": " + row.image;
    if (Status s = CheckTypedReadings(*check, where, row.legs, commanded); !s.ok()) return s;
  }
  return Status::Ok();
}

}  // namespace

Status ImportLegsFile(const std::string& dir, const std::string& legs_file) {
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kBriefly);
  if (!lock.ok()) return lock.status();
  StatusOr<std::string> text = ReadFileToString(legs_file, kMaxTableBytes);
  if (!text.ok()) return text.status();
  const std::string path = SessionPaths(dir).legs;
  std::error_code error;
  const bool had_one = fs::exists(fs::symlink_status(path, error));
  StatusOr<std::string> previous = had_one ? ReadFileToString(path, kMaxTableBytes) : StatusOr<std::string>("");
  if (!previous.ok()) return previous.status();
  if (Status s = WriteFileAtomically(path, *text); !s.ok()) return s;
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(dir);
  Status loaded = rows.ok() ? Status::Ok() : rows.status();
  if (rows.ok()) loaded = CheckImportedReadings(dir, legs_file, *rows, CommandedPoses(*previous, path));
  if (loaded.ok()) return Status::Ok();
  const Status restored = had_one ? WriteFileAtomically(path, *previous) : Status::Ok();
  if (!had_one) fs::remove(path, error);
  return restored.ok() ? loaded : restored;
}

EditOutcome ApplyPlanEdit(const std::string& dir, const std::vector<Vector6d>& seen,
                          const std::vector<Vector6d>& wanted, const EditOptions& options) {
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, options.wait);
  if (!lock.ok()) return Failed(lock.status());
  const std::string path = SessionPaths(dir).plan;
  std::error_code error;
  std::vector<Vector6d> on_disk;
  if (fs::exists(fs::symlink_status(path, error))) {
    StatusOr<std::vector<Vector6d>> loaded = LoadPoses(path);
    if (!loaded.ok() && !options.overwrite) return Conflict(loaded.status().message());
    if (loaded.ok()) on_disk = *loaded;
  }
  if (on_disk != seen && !options.overwrite) {
    return Conflict("plan.csv changed on disk since it was shown (" + std::to_string(on_disk.size()) + " poses there, " +
                    std::to_string(seen.size()) + " shown): another program wrote it");
  }
  if (wanted.empty()) {
    fs::remove(path, error);
    return error ? Failed(Status::IoError(path + ": cannot remove: " + error.message())) : Done();
  }
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return Failed(config.status());
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  if (!robot.ok()) return Failed(robot.status());
  return Failed(WritePlanCsv(path, PlanningModel{*robot, std::nullopt, std::nullopt}, wanted));
}

EditOutcome ApplyCameraEdit(const std::string& dir, const std::string& seen, const std::string& wanted,
                            const EditOptions& options) {
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, options.wait);
  if (!lock.ok()) return Failed(lock.status());
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return Failed(config.status());
  if (config->camera != seen && !options.overwrite) {
    return Conflict("session.yaml: the camera is " + Excerpt(config->camera) + " on disk, not " + Excerpt(seen) +
                    " as shown (another program changed it)");
  }
  config->camera = wanted;
  return Failed(SaveSessionConfig(dir, *config));
}

Status RemoveCapture(const std::string& dir, const std::string& image, LockWait wait) {
  if (Status s = RefuseInPointsSession(dir, "remove a capture"); !s.ok()) return s;
  if (Status s = CheckImageName(image); !s.ok()) return s;
  if (Status s = CheckWritableInside(dir, "images"); !s.ok()) return s;
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, wait);
  if (!lock.ok()) return lock.status();
  StatusOr<CsvTable> table = ReadLegsTable(SessionPaths(dir).legs, "image");
  if (!table.ok()) return table.status();
  const int row = RowOf(*table, "image", image);
  // The row first: a kill before the image goes leaves an image without a
  // row, which the next capture of the pose records again (acquire_step.h).
  if (row >= 0) {
    table->rows.erase(table->rows.begin() + row);
    if (Status s = WriteFileAtomically(SessionPaths(dir).legs, FormatCsv(table->header, table->rows)); !s.ok())
      return s;
  }
  const fs::path file = fs::path(SessionPaths(dir).images) / image;
  std::error_code error;
  const bool had_image = fs::remove(file, error);
  if (error) return Status::IoError(file.string() + ": cannot remove: " + error.message());
  if (row < 0 && !had_image) return Status::BadInput(image + ": neither in legs.csv nor in images/");
  return Status::Ok();
}

}  // namespace hexcal::workflow

#include "workflow/session_measure.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/session.h"
#include "core/sha256.h"
#include "session/json_fields.h"
#include "session/session_models.h"
#include "session/session_results.h"
#include "vision/measure.h"

namespace hexcal::workflow {
namespace {

// The status column of a row of camera_poses.csv as written.
std::string StatusCell(const ImageMeasurementRecord& row) {
  static const std::vector<std::string> columns = ImageMeasurementColumns();
  static const size_t column =
      static_cast<size_t>(std::find(columns.begin(), columns.end(), "status") - columns.begin());
  return column < row.cells.size() ? row.cells[column] : "";
}

namespace fs = std::filesystem;

// What camera_poses.csv was measured with: SHA-256 of the camera file, the
// target file and each image (camera_poses.json), and of the table itself as
// hexcal wrote it, so that a table edited by hand is measured again.
struct MeasuredWith {
  std::string camera, target, table;
  std::map<std::string, std::string> images;
};

std::string RecordPath(const std::string& dir) { return (fs::path(dir) / "camera_poses.json").string(); }

// The record on disk; an empty one when it is missing or does not read (then
// every row is measured again, which is always safe).
MeasuredWith ReadRecord(const std::string& dir) {
  MeasuredWith record;
  StatusOr<std::string> text = ReadFileToString(RecordPath(dir), kMaxJsonBytes);
  if (!text.ok()) return record;
  StatusOr<nlohmann::json> json = ParseJsonText(*text, RecordPath(dir));
  if (!json.ok() || !json->is_object()) return record;
  JsonFields fields(*json, RecordPath(dir));
  record.camera = fields.String("camera");
  record.target = fields.String("target");
  if (const auto table = json->find("table"); table != json->end() && table->is_string())
    record.table = table->get<std::string>();
  const auto images = json->find("images");
  if (!fields.status().ok() || images == json->end() || !images->is_object()) return MeasuredWith{};
  for (const auto& [name, hash] : images->items())
    if (hash.is_string()) record.images[name] = hash.get<std::string>();
  return record;
}

Status WriteRecord(const std::string& dir, const MeasuredWith& record) {
  const nlohmann::json json{{"format", 1}, {"camera", record.camera}, {"target", record.target},
                            {"table", record.table}, {"images", record.images}};
  const std::string text = json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  return WriteFileAtomically(RecordPath(dir), text + "\n");
}

// The hash under `key` in `known` (named as HashSessionInputs names them),
// else computed: a calibration has just hashed every input once already.
StatusOr<std::string> KnownOr(const ContentHashes* known, const std::string& key,
                              const std::function<StatusOr<std::string>()>& compute) {
  if (known != nullptr)
    if (const auto found = known->find(key); found != known->end()) return found->second;
  return compute();
}

StatusOr<MeasuredWith> CurrentInputs(const std::string& dir, const std::vector<std::string>& images,
                                     const ContentHashes* known) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  MeasuredWith now;
  StatusOr<std::string> camera =
      KnownOr(known, "camera " + config->camera, [&] { return HashSessionFile(dir, config->camera); });
  if (!camera.ok()) return camera.status();
  StatusOr<std::string> target =
      KnownOr(known, "target " + config->target, [&] { return HashSessionFile(dir, config->target); });
  if (!target.ok()) return target.status();
  now.camera = *camera;
  now.target = *target;
  for (const std::string& image : images) {
    StatusOr<std::string> hash = KnownOr(known, "images/" + image, [&] {
      return Sha256OfFile((fs::path(SessionPaths(dir).images) / image).string(), kMaxImageBytes);
    });
    if (!hash.ok()) return hash.status();
    now.images[image] = *hash;
  }
  return now;
}

// The images to measure: those without a row, those whose file changed, all
// of them when the camera or the target changed (or when asked).
MeasureState PlanMeasuring(const MeasuredWith& record, const MeasuredWith& now, const std::set<std::string>& rows,
                           const std::vector<std::string>& images, bool all) {
  MeasureState state;
  if (all) {
    state.to_measure = images;
    state.reason = "measuring every image again, as asked";
  } else if (!rows.empty() && (record.camera.empty() || record.target.empty() || record.table.empty())) {
    state.to_measure = images;
    state.reason = "camera_poses.csv has no record of the camera and target it was measured with (camera_poses.json)";
  } else if (!rows.empty() && record.table != now.table) {
    state.to_measure = images;
    state.reason = "camera_poses.csv was changed by another program since hexcal wrote it";
  } else if (!rows.empty() && (record.camera != now.camera || record.target != now.target)) {
    state.to_measure = images;
    state.reason = std::string("the ") + (record.camera != now.camera ? "camera" : "target") +
                   " changed since the images were measured";
  }
  if (!state.to_measure.empty()) return state;
  int changed = 0;
  for (const std::string& image : images) {
    const auto old = record.images.find(image);
    const bool replaced = rows.count(image) > 0 && (old == record.images.end() || old->second != now.images.at(image));
    if (rows.count(image) == 0 || replaced) state.to_measure.push_back(image);
    changed += replaced;
  }
  if (changed > 0) state.reason = std::to_string(changed) + " image(s) changed since they were measured";
  return state;
}

}  // namespace

namespace {

// camera_poses.csv as it is: the poses by image and every row's cells, and
// the SHA-256 of its bytes in `hash` ("" when there is no table).
StatusOr<std::vector<ImageMeasurementRecord>> ReadMeasurementRows(const std::string& path, std::string* hash) {
  hash->clear();
  std::error_code error;
  if (!fs::exists(path, error)) return std::vector<ImageMeasurementRecord>{};
  StatusOr<std::string> text = ReadFileToString(path, kMaxTableBytes);
  if (!text.ok()) return text.status();
  *hash = Sha256Hex(*text);
  return ParseImageMeasurementsCsv(*text, path);
}

std::set<std::string> RowImages(const std::vector<ImageMeasurementRecord>& rows) {
  std::set<std::string> images;
  for (const ImageMeasurementRecord& row : rows) images.insert(row.file);
  return images;
}

}  // namespace

StatusOr<MeasureState> SessionMeasureState(const std::string& dir, const std::vector<std::string>& images,
                                           const ContentHashes* known_hashes) {
  std::string table;
  StatusOr<std::vector<ImageMeasurementRecord>> rows = ReadMeasurementRows(SessionPaths(dir).camera_poses, &table);
  if (!rows.ok()) return rows.status();
  StatusOr<MeasuredWith> now = CurrentInputs(dir, images, known_hashes);
  if (!now.ok()) return now.status();
  now->table = table;
  return PlanMeasuring(ReadRecord(dir), *now, RowImages(*rows), images, false);
}

StatusOr<SessionMeasurements> MeasureSessionImages(const std::string& dir, const std::vector<std::string>& images,
                                                   const Camera& camera, const Target& target,
                                                   const MeasureSessionOptions& options, const JobHooks& hooks) {
  const SessionPaths paths(dir);
  std::string table;
  StatusOr<std::vector<ImageMeasurementRecord>> rows = ReadMeasurementRows(paths.camera_poses, &table);
  if (!rows.ok()) return rows.status();
  StatusOr<MeasuredWith> now = CurrentInputs(dir, images, options.known_hashes);
  if (!now.ok()) return now.status();
  now->table = table;
  MeasuredWith record = ReadRecord(dir);
  const MeasureState plan = PlanMeasuring(record, *now, RowImages(*rows), images, options.all);
  const std::set<std::string> doomed(plan.to_measure.begin(), plan.to_measure.end());
  SessionMeasurements result;
  result.remeasure_reason = plan.reason;
  std::vector<std::vector<std::string>> cells;
  for (ImageMeasurementRecord& row : *rows) {
    if (doomed.count(row.file) > 0) continue;
    result.poses[row.file] = SessionImagePose{row.ok, StatusCell(row), row.camera_from_target, row.covariance};
    result.reused += std::count(images.begin(), images.end(), row.file) > 0;
    cells.push_back(std::move(row.cells));
  }
  if (plan.to_measure.empty()) return result;
  if (!plan.reason.empty()) hooks.Note("measuring " + std::to_string(plan.to_measure.size()) + " images: " + plan.reason);
  hooks.Stage("measure (images)");
  std::vector<std::string> files;
  for (const std::string& image : plan.to_measure) files.push_back((fs::path(paths.images) / image).string());
  MeasureOptions measure;
  measure.keep_observations = options.keep_observations;
  StatusOr<std::vector<ImageMeasurement>> measured = MeasureImages(files, camera, target, measure, hooks);
  if (!measured.ok()) return measured.status();
  for (ImageMeasurement m : *measured) {
    m.file = fs::path(m.file).filename().string();
    if (m.observation && m.pose.status == PoseStatus::kOk) result.observations[m.file] = std::move(*m.observation);
    result.poses[m.file] = SessionImagePose{m.pose.status == PoseStatus::kOk, PoseStatusName(m.pose.status),
                                            m.pose.camera_from_target, m.pose.covariance_vector};
    cells.push_back(ImageMeasurementRow(m));
  }
  result.measured = static_cast<int>(measured->size());
  // The table first, then its record: a kill between them leaves an old
  // record, which only makes the next run measure again.
  const std::string written = FormatCsv(ImageMeasurementColumns(), cells);
  if (Status s = WriteFileAtomically(paths.camera_poses, written); !s.ok()) return s;
  if (record.camera != now->camera || record.target != now->target || record.table != now->table)
    record.images.clear();
  record.camera = now->camera;
  record.target = now->target;
  record.table = Sha256Hex(written);
  for (const std::string& image : plan.to_measure) record.images[image] = now->images.at(image);
  if (Status s = WriteRecord(dir, record); !s.ok()) return s;
  return result;
}

StatusOr<SessionMeasurements> MeasureSessionFolder(const MeasureFolderRequest& request, const JobHooks& hooks) {
  const std::string& dir = request.session;
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, request.wait);
  if (!lock.ok()) return lock.status();
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config->camera));
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(dir, config->target));
  if (!target.ok()) return target.status();
  StatusOr<std::vector<std::string>> files = ListImages(SessionPaths(dir).images);
  if (!files.ok()) return files.status();
  std::vector<std::string> images;
  for (const std::string& file : *files) images.push_back(fs::path(file).filename().string());
  MeasureSessionOptions options;
  options.all = request.all;
  return MeasureSessionImages(dir, images, *camera, *target, options, hooks);
}

}  // namespace hexcal::workflow

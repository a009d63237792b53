#include "session/session_study.h"

#include <cassert>
#include <filesystem>
#include <iterator>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/staged_folder.h"
#include "session/json_fields.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

constexpr const char* kStudyJson = "study.json";
constexpr const char* kSubsetsCsv = "subsets.csv";

std::string PosesText(const std::vector<int>& poses) {
  std::string text;
  for (int j : poses) text += (text.empty() ? "" : " ") + std::to_string(j);
  return text;
}

// One row per subset: 0 the selected one, then the random ones in draw order.
// A subset that was not calibrated and validated has no errors (empty cells).
std::vector<std::string> SubsetRow(int subset, const SubsetOutcome& outcome) {
  std::vector<std::string> row = {std::to_string(subset), outcome.ok ? "1" : "0", PosesText(outcome.poses)};
  for (SubsetMetric metric : kSubsetMetrics) {
    const bool known = HigherIsBetter(metric) || outcome.ok;
    row.push_back(known ? FormatNumber(MetricValue(outcome, metric)) : "");
  }
  return row;
}

std::vector<std::string> SubsetsHeader() {
  std::vector<std::string> header = {"subset", "ok", "poses"};
  for (SubsetMetric metric : kSubsetMetrics) header.push_back(SubsetMetricName(metric));
  return header;
}

std::string SubsetsCsv(const SubsetStudyResult& result) {
  std::vector<std::vector<std::string>> rows = {SubsetRow(0, result.selected)};
  for (size_t k = 0; k < result.random.size(); ++k)
    rows.push_back(SubsetRow(static_cast<int>(k + 1), result.random[k]));
  return FormatCsv(SubsetsHeader(), rows);
}

// The random subsets' values per metric (rows 1..K), as RandomValues gives them.
StatusOr<std::vector<std::vector<double>>> ReadRandomValues(const std::string& path, const StudyRecord& record) {
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return table.status();
  if (table->rows.size() != static_cast<size_t>(record.random_count) + 1)
    return Status::BadInput(path + ": " + std::to_string(table->rows.size()) + " rows, study.json has " +
                            std::to_string(record.random_count) + " random subsets and the selected one");
  StatusOr<int> ok_column = ColumnIndex(*table, "ok");
  if (!ok_column.ok()) return ok_column.status();
  std::vector<std::vector<double>> values(std::size(kSubsetMetrics));
  for (size_t m = 0; m < values.size(); ++m) {
    const SubsetMetric metric = kSubsetMetrics[m];
    StatusOr<int> column = ColumnIndex(*table, SubsetMetricName(metric));
    if (!column.ok()) return column.status();
    for (size_t r = 1; r < table->rows.size(); ++r) {
      if (!HigherIsBetter(metric) && table->rows[r][*ok_column] != "1") continue;
      StatusOr<double> value = NumberAt(*table, r, *column);
      if (!value.ok()) return value.status();
      values[m].push_back(*value);
    }
    if (static_cast<int>(values[m].size()) != record.Metric(metric).random.count)
      return Status::BadInput(path + ": does not match study.json (" + SubsetMetricName(metric) +
                              "): run hexcal study again");
  }
  return values;
}

}  // namespace

std::string StudyFolderPath(const std::string& session_dir) { return (fs::path(session_dir) / "study").string(); }

bool HasSessionStudy(const std::string& session_dir) {
  std::error_code error;
  return fs::exists(fs::path(StudyFolderPath(session_dir)) / kStudyJson, error);
}

Status SaveSessionStudy(StudyOutcome* outcome, LockWait wait) {
  const std::string& dir = outcome->request.session;
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, wait);
  if (!lock.ok()) return lock.status();
  const std::string folder = StudyFolderPath(dir);
  StatusOr<StagedFolder> staged = StagedFolder::Begin(folder);
  if (!staged.ok()) return staged.status();
  std::vector<std::string> figures;  // in the staging folder: not the paths to report
  if (Status s = WriteStudyFigures(*outcome, staged->Path(), &figures); !s.ok()) return s;
  if (Status s = WriteFileAtomically(staged->File(kSubsetsCsv), SubsetsCsv(outcome->result)); !s.ok()) return s;
  StudyRecord record = MakeStudyRecord(*outcome);
  record.saved = folder;
  // A file name that is not UTF-8 is written with U+FFFD, never thrown on (as the results manifest).
  const std::string json = ToJson(record).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  if (Status s = WriteFileAtomically(staged->File(kStudyJson), json); !s.ok()) return s;
  if (Status s = staged->Publish(); !s.ok()) return s;
  outcome->saved = folder;
  return Status::Ok();
}

const std::vector<double>& SessionStudy::RandomValuesOf(SubsetMetric metric) const {
  for (size_t m = 0; m < std::size(kSubsetMetrics); ++m)
    if (kSubsetMetrics[m] == metric) return random_values[m];
  assert(false && "every metric has its values");
  return random_values.front();
}

StatusOr<SessionStudy> LoadSessionStudy(const std::string& dir, const ContentHashes* inputs) {
  const fs::path folder = StudyFolderPath(dir);
  const std::string json_path = (folder / kStudyJson).string();
  StatusOr<std::string> text = ReadFileToString(json_path, kMaxJsonBytes);
  if (!text.ok()) return text.status();
  StatusOr<nlohmann::json> json = ParseJsonText(*text, json_path);
  if (!json.ok()) return json.status();
  StatusOr<StudyRecord> record = StudyRecordFromJson(*json, json_path);
  if (!record.ok()) return record.status();
  StatusOr<std::vector<std::vector<double>>> values = ReadRandomValues((folder / kSubsetsCsv).string(), *record);
  if (!values.ok()) return values.status();
  SessionStudy study{std::move(*record), std::move(*values), {}};
  StatusOr<ContentHashes> now = inputs ? StatusOr<ContentHashes>(*inputs) : HashSessionInputs(dir);
  study.changed_inputs = now.ok() ? DifferingNames(study.record.inputs, *now)
                                  : std::vector<std::string>{"the session (" + now.status().message() + ")"};
  return study;
}

}  // namespace hexcal::workflow

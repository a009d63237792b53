#include "session/readings_table.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include "core/csv.h"
#include "core/point_file.h"
#include "core/session.h"
#include "session/session_models.h"
#include "vision/measure.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

std::set<std::string> ImageNames(const std::string& folder) {
  std::set<std::string> names;
  std::error_code error;
  if (!fs::is_directory(folder, error)) return names;
  StatusOr<std::vector<std::string>> files = ListImages(folder);
  if (files.ok())
    for (const std::string& file : *files) names.insert(fs::path(file).filename().string());
  return names;
}

// The poses a points session's points file has; none when it does not load
// (yet: the tracker may write it later).
std::set<std::string> PoseNames(const std::string& dir, const SessionConfig& config) {
  std::set<std::string> names;
  StatusOr<PointSets> sets = LoadPointFile(ResolveSessionFile(dir, config.points), config.point_sigma, config.points);
  if (sets.ok())
    for (const PointSet& set : *sets) names.insert(set.pose);
  return names;
}

// legs.csv's rows as cells, keyed by `key`; a missing file has none.
StatusOr<std::vector<ReadingsRow>> RecordedRows(const std::string& path, const std::string& key,
                                                const std::set<std::string>& images) {
  std::error_code error;
  if (!fs::exists(fs::symlink_status(path, error))) return std::vector<ReadingsRow>{};
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return table.status();
  StatusOr<int> image = ColumnIndex(*table, key);
  if (!image.ok()) return image.status();
  std::array<int, kNumLegs> legs{};
  for (int i = 0; i < kNumLegs; ++i) {
    StatusOr<int> column = ColumnIndex(*table, "L" + std::to_string(i + 1));
    if (!column.ok()) return column.status();
    legs[i] = *column;
  }
  const auto holdout = std::find(table->header.begin(), table->header.end(), "holdout");
  std::array<int, 6> commanded{};
  bool has_commanded = true;
  for (int k = 0; k < 6; ++k) {
    const auto it = std::find(table->header.begin(), table->header.end(), kCommandedColumns[k]);
    has_commanded = has_commanded && it != table->header.end();
    commanded[k] = static_cast<int>(it - table->header.begin());
  }
  std::vector<ReadingsRow> rows;
  for (size_t r = 0; r < table->rows.size(); ++r) {
    ReadingsRow row;
    row.image = table->rows[r][*image];
    row.recorded = true;
    row.image_present = images.count(row.image) > 0;
    for (int i = 0; i < kNumLegs; ++i) {
      StatusOr<double> value = NumberAt(*table, r, legs[i]);
      if (value.ok()) row.legs[i] = *value;
    }
    if (holdout != table->header.end()) row.holdout = table->rows[r][holdout - table->header.begin()] == "1";
    if (has_commanded) {
      StatusOr<std::optional<Vector6d>> pose = CommandedPoseAt(*table, r, commanded, "");
      if (pose.ok()) row.commanded = *pose;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

StatusOr<std::vector<ReadingsRow>> ReadReadingsTable(const std::string& dir) {
  const SessionPaths paths(dir);
  // A session.yaml that does not load: read as a camera session's (the status says what is wrong).
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  const bool points = config.ok() && config->instrument == Instrument::kPoints;
  const std::set<std::string> images = points ? PoseNames(dir, *config) : ImageNames(paths.images);
  StatusOr<std::vector<ReadingsRow>> rows = RecordedRows(paths.legs, MeasurementNoun(points ? Instrument::kPoints : Instrument::kCamera), images);
  if (!rows.ok()) return rows.status();
  std::set<std::string> recorded;
  for (const ReadingsRow& row : *rows) recorded.insert(row.image);
  for (const std::string& image : images) {
    if (recorded.count(image) > 0) continue;
    ReadingsRow row;
    row.image = image;
    row.image_present = true;
    rows->push_back(row);
  }
  return rows;
}

std::optional<std::array<double, kNumLegs>> ParseReadingsLine(const std::string& line) {
  std::string spaced = line;
  std::replace_if(spaced.begin(), spaced.end(), [](char c) { return c == '\t' || c == ',' || c == ';'; }, ' ');
  std::istringstream words(spaced);
  std::vector<double> numbers;
  std::string word;
  while (words >> word) {
    StatusOr<double> number = ParseNumber(word);
    if (number.ok()) {
      numbers.push_back(*number);
    } else if (!numbers.empty()) {
      return std::nullopt;  // text after the readings
    }
  }
  // A trailing holdout flag (0/1) after the six readings is left to the table.
  if (numbers.size() != kNumLegs && numbers.size() != kNumLegs + 1) return std::nullopt;
  std::array<double, kNumLegs> readings{};
  std::copy_n(numbers.begin(), kNumLegs, readings.begin());
  return readings;
}

}  // namespace hexcal::workflow

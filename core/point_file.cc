#include "core/point_file.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"

namespace hexcal {
namespace {

// Adds `point` to its pose's set, refusing a point given twice in one pose.
Status AddPoint(const std::string& pose, NamedPoint point, const std::string& where, PointSets* sets,
                std::map<std::string, size_t>* index) {
  if (!(point.sigma > 0)) return Status::BadInput(where + ": sigma must be positive");
  auto [it, added] = index->emplace(pose, sets->size());
  if (added) sets->push_back({pose, {}});
  std::vector<NamedPoint>& points = (*sets)[it->second].points;
  for (const NamedPoint& other : points)
    if (other.name == point.name)
      return Status::BadInput(where + ": point '" + point.name + "' of pose '" + pose + "' is given twice");
  points.push_back(std::move(point));
  return Status::Ok();
}

StatusOr<PointSets> ParseCsvPoints(const std::string& text, const std::string& source, double default_sigma) {
  StatusOr<CsvTable> table = ParseCsv(text, source);
  if (!table.ok()) return table.status();
  int columns[5];
  const char* names[5] = {"pose", "point", "x", "y", "z"};
  for (int k = 0; k < 5; ++k) {
    StatusOr<int> column = ColumnIndex(*table, names[k]);
    if (!column.ok()) return column.status();
    columns[k] = *column;
  }
  StatusOr<int> sigma_column = ColumnIndex(*table, "sigma");
  PointSets sets;
  std::map<std::string, size_t> index;
  for (size_t row = 0; row < table->rows.size(); ++row) {
    NamedPoint point{table->rows[row][static_cast<size_t>(columns[1])], {}, default_sigma};
    for (int k = 0; k < 3; ++k) {
      StatusOr<double> value = NumberAt(*table, row, columns[2 + k]);
      if (!value.ok()) return value.status();
      point.position[k] = *value;
    }
    if (sigma_column.ok()) {
      StatusOr<double> sigma = NumberAt(*table, row, *sigma_column);
      if (!sigma.ok()) return sigma.status();
      point.sigma = *sigma;
    }
    const std::string where = source + ":" + std::to_string(table->line_numbers[row]);
    if (Status s = AddPoint(table->rows[row][static_cast<size_t>(columns[0])], point, where, &sets, &index); !s.ok())
      return s;
  }
  return sets;
}

// The fields of one SpatialAnalyzer line: spaces, tabs and commas separate.
std::vector<std::string> Fields(std::string line) {
  for (char& c : line)
    if (c == ',' || c == '\t' || c == '\r') c = ' ';
  std::istringstream words(line);
  std::vector<std::string> fields;
  for (std::string word; words >> word;) fields.push_back(word);
  return fields;
}

bool Skipped(const std::string& line) {
  const std::vector<std::string> fields = Fields(line);
  return fields.empty() || fields[0].rfind("//", 0) == 0 || fields[0][0] == '#';
}

StatusOr<PointSets> ParseSpatialAnalyzer(const std::string& text, const std::string& source, double default_sigma) {
  PointSets sets;
  std::map<std::string, size_t> index;
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    if (Skipped(line)) continue;
    const std::vector<std::string> fields = Fields(line);
    const std::string where = source + ":" + std::to_string(number);
    if (fields.size() != 6 && fields.size() != 7)
      return Status::BadInput(where + ": expected collection, group, target, x, y, z and an optional sigma, got " +
                              std::to_string(fields.size()) + " fields");
    NamedPoint point{fields[2], {}, default_sigma};
    for (size_t k = 3; k < fields.size(); ++k) {
      StatusOr<double> value = ParseNumber(fields[k]);
      if (!value.ok()) return Status::BadInput(where + ": field " + std::to_string(k + 1) + " is not a number");
      if (k < 6) point.position[static_cast<int>(k - 3)] = *value;
      else point.sigma = *value;
    }
    if (Status s = AddPoint(fields[1], point, where, &sets, &index); !s.ok()) return s;
  }
  if (sets.empty()) return Status::BadInput(source + ": no points");
  return sets;
}

}  // namespace

StatusOr<PointSets> ParsePointFile(const std::string& text, const std::string& source, double default_sigma) {
  std::string body = text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text;
  std::istringstream lines(body);
  std::string first;
  while (std::getline(lines, first) && Skipped(first)) {
  }
  const std::vector<std::string> fields = Fields(first);
  const auto has = [&](const char* name) { return std::find(fields.begin(), fields.end(), name) != fields.end(); };
  const bool csv = has("pose") && has("point");
  return csv ? ParseCsvPoints(body, source, default_sigma) : ParseSpatialAnalyzer(body, source, default_sigma);
}

StatusOr<std::vector<NamedPoint>> ParseReflectorFile(const std::string& text, const std::string& source) {
  StatusOr<CsvTable> table = ParseCsv(text, source);
  if (!table.ok()) return table.status();
  int columns[4];
  const char* names[4] = {"point", "x", "y", "z"};
  for (int k = 0; k < 4; ++k) {
    StatusOr<int> column = ColumnIndex(*table, names[k]);
    if (!column.ok()) return column.status();
    columns[k] = *column;
  }
  std::vector<NamedPoint> reflectors;
  std::set<std::string> seen;
  for (size_t row = 0; row < table->rows.size(); ++row) {
    NamedPoint point{table->rows[row][static_cast<size_t>(columns[0])], {}, 0};
    if (!seen.insert(point.name).second)
      return Status::BadInput(source + ":" + std::to_string(table->line_numbers[row]) + ": reflector '" + point.name +
                              "' is given twice");
    for (int k = 0; k < 3; ++k) {
      StatusOr<double> value = NumberAt(*table, row, columns[1 + k]);
      if (!value.ok()) return value.status();
      point.position[k] = *value;
    }
    reflectors.push_back(point);
  }
  return reflectors;
}

StatusOr<PointSets> LoadPointFile(const std::string& path, double default_sigma, const std::string& source) {
  StatusOr<std::string> text = ReadFileToString(path, kMaxTableBytes);
  if (!text.ok()) return text.status();
  return ParsePointFile(*text, source.empty() ? path : source, default_sigma);
}

StatusOr<std::vector<NamedPoint>> LoadReflectorFile(const std::string& path, const std::string& source) {
  StatusOr<std::string> text = ReadFileToString(path, kMaxTableBytes);
  if (!text.ok()) return text.status();
  return ParseReflectorFile(*text, source.empty() ? path : source);
}

}  // namespace hexcal

#include "core/measurements.h"

#include <array>

#include "core/csv.h"
#include "core/table_kind.h"

namespace hexcal {
namespace {

constexpr int kNumColumns = 12;  // six pose coordinates, six readings

StatusOr<std::vector<Measurement>> FromTable(const CsvTable& table) {
  const std::vector<std::string>& names = MeasurementColumns();
  std::array<int, kNumColumns> columns;
  for (int k = 0; k < kNumColumns; ++k) {
    StatusOr<int> column = ColumnIndex(table, names[k]);
    if (!column.ok()) {
      return Status::BadInput(column.status().message() + TableKindHint(table.header, TableKind::kRobotMeasurements));
    }
    columns[k] = *column;
  }
  if (table.rows.empty()) {
    return Status::BadInput(table.source + ": no measurements (the file has a header but no data rows)");
  }
  std::vector<Measurement> measurements(table.rows.size());
  for (size_t row = 0; row < table.rows.size(); ++row) {
    for (int k = 0; k < kNumColumns; ++k) {
      StatusOr<double> value = NumberAt(table, row, columns[k]);
      if (!value.ok()) return value.status();
      if (k < 6) {
        measurements[row].pose[k] = *value;
      } else {
        measurements[row].legs[k - 6] = *value;
      }
    }
  }
  return measurements;
}

}  // namespace

const std::vector<std::string>& MeasurementColumns() {
  static const std::vector<std::string> columns = {"x", "y", "z", "q1", "q2", "q3", "L1", "L2", "L3", "L4", "L5", "L6"};
  return columns;
}

StatusOr<std::vector<Measurement>> LoadMeasurements(const std::string& path) {
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return table.status();
  return FromTable(*table);
}

StatusOr<std::vector<Measurement>> ParseMeasurements(const std::string& text, const std::string& source) {
  StatusOr<CsvTable> table = ParseCsv(text, source);
  if (!table.ok()) return table.status();
  return FromTable(*table);
}

Status SaveMeasurements(const std::string& path, const std::vector<Measurement>& measurements) {
  std::vector<std::vector<std::string>> rows;
  rows.reserve(measurements.size());
  for (const Measurement& m : measurements) {
    std::vector<std::string> row;
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(m.pose[k]));
    for (int i = 0; i < kNumLegs; ++i) row.push_back(FormatNumber(m.legs[i]));
    rows.push_back(std::move(row));
  }
  return WriteCsv(path, MeasurementColumns(), rows);
}

}  // namespace hexcal

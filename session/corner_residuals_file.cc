#include "session/corner_residuals_file.h"

#include <map>

#include "core/csv.h"

namespace hexcal::workflow {
namespace {

const std::vector<std::string> kHeader = {"image", "tag_id", "corner", "x_px", "y_px", "dx_px", "dy_px"};

// The integer cell at (row, col): tag ids and corners 0..3.
StatusOr<int> IntegerAt(const CsvTable& table, size_t row, int col) {
  StatusOr<double> value = NumberAt(table, row, col);
  if (!value.ok()) return value.status();
  if (*value != static_cast<int>(*value) || *value < 0)
    return Status::BadInput(table.source + ":" + std::to_string(table.line_numbers[row]) + ": column '" +
                            table.header[col] + "': not a whole number >= 0");
  return static_cast<int>(*value);
}

}  // namespace

Status SaveCornerResiduals(const std::string& path, const CornerResidualTable& table) {
  std::vector<std::vector<std::string>> rows;
  for (const CornerResidual& c : table.corners) {
    rows.push_back({table.images.at(static_cast<size_t>(c.image)), std::to_string(c.tag_id), std::to_string(c.corner),
                    FormatNumber(c.observed.x()), FormatNumber(c.observed.y()), FormatNumber(c.residual.x()),
                    FormatNumber(c.residual.y())});
  }
  return WriteCsv(path, kHeader, rows);
}

StatusOr<CornerResidualTable> LoadCornerResiduals(const std::string& path) {
  StatusOr<CsvTable> csv = ReadCsv(path);
  if (!csv.ok()) return csv.status();
  std::vector<int> column;
  for (const std::string& name : kHeader) {
    StatusOr<int> index = ColumnIndex(*csv, name);
    if (!index.ok()) return index.status();
    column.push_back(*index);
  }
  CornerResidualTable table;
  std::map<std::string, int> image_index;
  for (size_t r = 0; r < csv->rows.size(); ++r) {
    CornerResidual c;
    const std::string& image = csv->rows[r][column[0]];
    const auto [found, added] = image_index.emplace(image, static_cast<int>(table.images.size()));
    if (added) table.images.push_back(image);
    c.image = found->second;
    StatusOr<int> tag = IntegerAt(*csv, r, column[1]), corner = IntegerAt(*csv, r, column[2]);
    if (!tag.ok()) return tag.status();
    if (!corner.ok()) return corner.status();
    c.tag_id = *tag;
    c.corner = *corner;
    double values[4];
    for (int k = 0; k < 4; ++k) {
      StatusOr<double> value = NumberAt(*csv, r, column[3 + k]);
      if (!value.ok()) return value.status();
      values[k] = *value;
    }
    c.observed = {values[0], values[1]};
    c.residual = {values[2], values[3]};
    table.corners.push_back(c);
  }
  return table;
}

}  // namespace hexcal::workflow

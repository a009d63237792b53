#include "core/csv.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

#include "core/atomic_file.h"

namespace hexcal {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

std::string Trim(const std::string& text) {
  size_t begin = 0, end = text.size();
  while (begin < end && IsBlank(text[begin])) ++begin;
  while (end > begin && IsBlank(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

std::string Join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string joined;
  for (size_t i = 0; i < parts.size(); ++i) joined += (i ? separator : "") + parts[i];
  return joined;
}

std::string LinePrefix(const std::string& source, int line) { return source + ":" + std::to_string(line) + ": "; }

// Splits one line into trimmed fields. Quotes are honoured only around a
// whole field, so a stray quote inside a value is a typo, not data.
Status SplitFields(const std::string& line, std::vector<std::string>* fields) {
  fields->clear();
  size_t pos = 0;
  while (true) {
    const int field_number = static_cast<int>(fields->size()) + 1;
    while (pos < line.size() && IsBlank(line[pos])) ++pos;
    std::string field;
    if (pos < line.size() && line[pos] == '"') {
      ++pos;
      while (true) {
        if (pos >= line.size()) {
          return Status::BadInput("field " + std::to_string(field_number) + ": quoted field has no closing quote");
        }
        if (line[pos] == '"') {
          if (pos + 1 < line.size() && line[pos + 1] == '"') {
            field += '"';
            pos += 2;
            continue;
          }
          ++pos;
          break;
        }
        field += line[pos++];
      }
      while (pos < line.size() && IsBlank(line[pos])) ++pos;
      if (pos < line.size() && line[pos] != ',') {
        return Status::BadInput("field " + std::to_string(field_number) + ": text after the closing quote");
      }
    } else {
      const size_t comma = line.find(',', pos);
      const size_t end = comma == std::string::npos ? line.size() : comma;
      field = Trim(line.substr(pos, end - pos));
      if (field.find('"') != std::string::npos) {
        return Status::BadInput("field " + std::to_string(field_number) +
                                ": quote inside an unquoted field (quote the whole field)");
      }
      pos = end;
    }
    fields->push_back(std::move(field));
    if (pos >= line.size()) return Status::Ok();
    ++pos;  // the comma
  }
}

bool IsBlankOrComment(const std::string& line) {
  for (char c : line) {
    if (IsBlank(c)) continue;
    return c == '#';
  }
  return true;
}

Status CheckHeader(const CsvTable& table, int line) {
  std::set<std::string> seen;
  for (size_t i = 0; i < table.header.size(); ++i) {
    const std::string& name = table.header[i];
    if (name.empty()) {
      return Status::BadInput(LinePrefix(table.source, line) + "header column " + std::to_string(i + 1) +
                              " has no name");
    }
    // A file without its header line starts with data, which would otherwise
    // be reported as a duplicate or a missing column.
    if (ParseNumber(name).ok()) {
      return Status::BadInput(LinePrefix(table.source, line) + "no header: column " + std::to_string(i + 1) +
                              " is the number " + Excerpt(name) + ", and the first line must name the columns");
    }
    if (!seen.insert(name).second) {
      return Status::BadInput(LinePrefix(table.source, line) + "duplicate column " + Excerpt(name) + " in header");
    }
  }
  return Status::Ok();
}

// One unquoted field's number, as NumberAt reads it (blanks trimmed, a leading
// '+' allowed); nullopt for anything NumberAt would refuse.
std::optional<double> PlainNumber(const char* begin, const char* end) {
  while (begin < end && IsBlank(*begin)) ++begin;
  while (end > begin && IsBlank(end[-1])) --end;
  if (begin == end) return std::nullopt;
  if (*begin == '+' && end - begin > 1 && begin[1] != '-' && begin[1] != '+') ++begin;
  double value = 0;
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (error != std::errc() || stop != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

// A table of 10⁵ poses as rows of strings costs more than its numbers.
std::optional<std::vector<Vector6d>> PlainSixColumns(const std::string& text, const std::array<const char*, 6>& names) {
  if (text.find('"') != std::string::npos) return std::nullopt;
  size_t pos = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  std::vector<std::string> header;
  std::array<int, 6> columns;
  std::vector<Vector6d> vectors;
  std::vector<std::pair<const char*, const char*>> fields;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const char* first = text.data() + pos;
    const char* last = text.data() + (end > pos && text[end - 1] == '\r' ? end - 1 : end);
    pos = end + 1;
    const char* nonblank = first;
    while (nonblank < last && IsBlank(*nonblank)) ++nonblank;
    if (nonblank == last || *nonblank == '#') continue;
    fields.clear();
    for (const char* field = first;; ++field) {
      const char* comma = std::find(field, last, ',');
      fields.emplace_back(field, comma);
      if (comma == last) break;
      field = comma;
    }
    if (header.empty()) {
      for (const auto& [begin, stop] : fields) header.push_back(Trim(std::string(begin, stop)));
      for (int k = 0; k < 6; ++k) {
        const auto found = std::find(header.begin(), header.end(), names[k]);
        if (found == header.end()) return std::nullopt;
        columns[k] = static_cast<int>(found - header.begin());
      }
      continue;
    }
    if (fields.size() != header.size()) return std::nullopt;
    Vector6d& row = vectors.emplace_back();
    for (int k = 0; k < 6; ++k) {
      const std::optional<double> value = PlainNumber(fields[columns[k]].first, fields[columns[k]].second);
      if (!value) return std::nullopt;
      row[k] = *value;
    }
  }
  if (vectors.empty() || !CheckHeader(CsvTable{"", header, {}, {}}, 1).ok()) return std::nullopt;
  return vectors;
}

namespace {

StatusOr<std::vector<Vector6d>> LoadSixColumns(const std::string& path, const std::array<const char*, 6>& names,
                                               const std::string& what) {
  StatusOr<std::string> text = ReadFileToString(path, kMaxTableBytes);
  if (!text.ok()) return text.status();
  if (std::optional<std::vector<Vector6d>> plain = PlainSixColumns(*text, names)) return std::move(*plain);
  StatusOr<CsvTable> table = ParseCsv(*text, path);
  if (!table.ok()) return table.status();
  std::array<int, 6> columns;
  for (int k = 0; k < 6; ++k) {
    StatusOr<int> column = ColumnIndex(*table, names[k]);
    if (!column.ok()) return column.status();
    columns[k] = *column;
  }
  if (table->rows.empty()) {
    return Status::BadInput(path + ": no " + what + " (the file has a header but no data rows)");
  }
  std::vector<Vector6d> vectors(table->rows.size());
  for (size_t row = 0; row < table->rows.size(); ++row) {
    for (int k = 0; k < 6; ++k) {
      StatusOr<double> value = NumberAt(*table, row, columns[k]);
      if (!value.ok()) return value.status();
      vectors[row][k] = *value;
    }
  }
  return vectors;
}

bool NeedsQuotes(const std::string& field) {
  if (field.empty() || field[0] == '#') return true;  // else a blank or comment line
  if (IsBlank(field.front()) || IsBlank(field.back())) return true;
  return field.find_first_of(",\"\r\n") != std::string::npos;
}

std::string QuoteIfNeeded(const std::string& field) {
  if (!NeedsQuotes(field)) return field;
  std::string quoted = "\"";
  for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void AppendCsvLine(const std::vector<std::string>& fields, std::string* text) {
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) *text += ',';
    *text += QuoteIfNeeded(fields[i]);
  }
  *text += '\n';
}

}  // namespace

StatusOr<CsvTable> ParseCsv(const std::string& text, const std::string& source) {
  CsvTable table;
  table.source = source;
  // Spreadsheet programs like to start a UTF-8 file with a byte-order mark.
  const size_t start = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  bool have_header = false;
  int line_number = 0;
  std::vector<std::string> fields;
  for (size_t pos = start; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (IsBlankOrComment(line)) continue;

    Status split = SplitFields(line, &fields);
    if (!split.ok()) return Status::BadInput(LinePrefix(source, line_number) + split.message());
    if (!have_header) {
      table.header = fields;
      have_header = true;
      Status header_ok = CheckHeader(table, line_number);
      if (!header_ok.ok()) return header_ok;
      continue;
    }
    if (fields.size() != table.header.size()) {
      return Status::BadInput(LinePrefix(source, line_number) + std::to_string(fields.size()) +
                              " columns, header has " + std::to_string(table.header.size()));
    }
    table.rows.push_back(fields);
    table.line_numbers.push_back(line_number);
  }
  if (!have_header) {
    return Status::BadInput(source + ": no header line (the file is empty or holds only comments)");
  }
  return table;
}

StatusOr<CsvTable> ReadCsv(const std::string& path) {
  StatusOr<std::string> text = ReadFileToString(path, kMaxTableBytes);
  if (!text.ok()) return text.status();
  return ParseCsv(*text, path);
}

StatusOr<double> ParseNumber(const std::string& text) {
  if (text.empty()) return Status::BadInput("expected a number, found nothing");
  // from_chars, unlike strtod, ignores the C locale but also refuses a '+' sign.
  size_t begin = 0;
  if (text[0] == '+' && text.size() > 1 && text[1] != '-' && text[1] != '+') begin = 1;
  double value = 0;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(text.data() + begin, last, value);
  if (error != std::errc() || end != last || !std::isfinite(value)) {
    return Status::BadInput(Excerpt(text) + " is not a finite number");
  }
  return value;
}

StatusOr<int> ColumnIndex(const CsvTable& table, const std::string& name) {
  for (size_t i = 0; i < table.header.size(); ++i) {
    if (table.header[i] == name) return static_cast<int>(i);
  }
  // The header is the file's first line, which may be anything: quote its start only.
  const std::string header = Excerpt(Join(table.header, ","));
  return Status::BadInput(table.source + ": missing column '" + name +
                          "' (header: " + header.substr(1, header.size() - 2) + ")");
}

StatusOr<double> NumberAt(const CsvTable& table, size_t row, int col) {
  assert(row < table.rows.size() && col >= 0 && col < static_cast<int>(table.header.size()));
  StatusOr<double> value = ParseNumber(table.rows[row][col]);
  if (value.ok()) return value;
  return Status::BadInput(LinePrefix(table.source, table.line_numbers[row]) + "column '" + table.header[col] +
                          "': " + value.status().message());
}

StatusOr<std::vector<Vector6d>> LoadPoses(const std::string& path) {
  return LoadSixColumns(path, {"x", "y", "z", "q1", "q2", "q3"}, "poses");
}

StatusOr<std::vector<Eigen::Matrix<double, 6, 1>>> LoadLegReadings(const std::string& path) {
  return LoadSixColumns(path, {"L1", "L2", "L3", "L4", "L5", "L6"}, "leg readings");
}

std::string FormatCsv(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::string text;
  AppendCsvLine(header, &text);
  for (const auto& row : rows) {
    assert(row.size() == header.size());
    AppendCsvLine(row, &text);
  }
  return text;
}

std::string Excerpt(const std::string& text, size_t max_chars) {
  std::string quoted = "'";
  size_t shown = 0;
  for (; shown < text.size() && shown < max_chars; ++shown) {
    const unsigned char c = static_cast<unsigned char>(text[shown]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      quoted += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
      quoted += escaped;
    }
  }
  return quoted + (shown < text.size() ? "...'" : "'");
}

bool IsPlainName(const std::string& key) {
  return !key.empty() && key.size() <= 40 && std::all_of(key.begin(), key.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_' || c == '-';
  });
}

std::string FormatSignificant(double v, int digits) {
  assert(digits >= 1 && digits <= 17);
  char buffer[32];  // to_chars writes "inf" and "nan" as printf does
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

std::string FormatNumber(double v) {
  assert(std::isfinite(v));
  // The %.<p>g forms (via to_chars: locale-independent) with the fewest digits
  // that read back exactly. A finer decimal grid contains the coarser one, so
  // the first precision that round-trips is the shortest; 17 always does.
  auto format_g = [v](int precision) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v, std::chars_format::general, precision);
    return std::string(buffer, result.ptr);
  };
  int precision = 1;
  std::string text = format_g(precision);
  for (; precision < 17; text = format_g(++precision)) {
    double parsed = 0;
    std::from_chars(text.data(), text.data() + text.size(), parsed);
    if (parsed == v) break;
  }
  // %g writes 20 as "2e+01" at precision 1; with as many digits as the integer
  // part has (still exact: a finer grid) it writes "20".
  const size_t e = text.find("e+");
  if (e != std::string::npos) {
    const int exponent = std::stoi(text.substr(e + 2));
    if (exponent >= precision && exponent < 17) text = format_g(exponent + 1);
  }
  return text;
}

Status WriteCsv(const std::string& path, const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows) {
  return WriteFileAtomically(path, FormatCsv(header, rows));
}

}  // namespace hexcal

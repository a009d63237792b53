// Strict CSV tables of numbers: pose lists, leg-length readings, measurements.
//
// Files are meant to be opened and edited by hand, so the reader forgives
// layout (spaces around fields, blank lines, '#' comment lines, CRLF line ends,
// columns in any order, extra columns) but not content: a wrong column count,
// a duplicate or missing column or a cell that is not a finite number is an
// error naming the file, the line and the column:
//   poses.csv:7: 5 columns, header has 6
//   poses.csv:9: column 'z': 'abc' is not a finite number
//
// Fields may be double-quoted to hold commas ("a,b"; "" inside quotes is one
// quote); a quoted field cannot span lines. Numbers are read and written
// independently of the C locale, which a Qt application sets from the
// environment.
//
//   StatusOr<std::vector<Vector6d>> poses = LoadPoses("plan.csv");
//   if (!poses.ok()) return poses.status();
//   Status saved = WriteCsv("out.csv", {"x", "y"}, {{FormatNumber(1.5), "2"}});
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/status.h"

namespace hexcal {

struct CsvTable {
  std::string source;                          // the path, used in every error message
  std::vector<std::string> header;             // trimmed column names, unique
  std::vector<std::vector<std::string>> rows;  // trimmed cells, header.size() each
  std::vector<int> line_numbers;               // 1-based file line of each row
};

StatusOr<CsvTable> ReadCsv(const std::string& path);
// The same, from text already in memory; `source` names it in messages.
StatusOr<CsvTable> ParseCsv(const std::string& text, const std::string& source);

// A finite double in C syntax ("-1.5e-3", "+2", "7"); rejects empty text,
// trailing characters, nan, inf and values that overflow a double.
StatusOr<double> ParseNumber(const std::string& text);

// Index of the column named `name` (exact, case-sensitive match).
StatusOr<int> ColumnIndex(const CsvTable& table, const std::string& name);
// The cell at (row, col) as a finite number. row and col must be in range.
StatusOr<double> NumberAt(const CsvTable& table, size_t row, int col);

// Poses [x, y, z, q1, q2, q3] (robot length unit, degrees) from a file with
// those six columns in any order; other columns are ignored. At least one row.
StatusOr<std::vector<Vector6d>> LoadPoses(const std::string& path);
// Leg sensor readings [L1..L6] from columns L1..L6, same rules as LoadPoses.
StatusOr<std::vector<Eigen::Matrix<double, 6, 1>>> LoadLegReadings(const std::string& path);
// Their fast path: the six named columns of a plain table's text (no quote
// anywhere, every data line the header's field count, every wanted cell a
// number, at least one row), read as the general reader would; nullopt for
// anything else, which the general reader then reads or reports on.
std::optional<std::vector<Vector6d>> PlainSixColumns(const std::string& text, const std::array<const char*, 6>& names);

// CSV text with "\n" line ends; fields that need it are double-quoted (commas,
// quotes, surrounding spaces, empty fields, a leading '#'). Every row must have
// header.size() fields.
std::string FormatCsv(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
// The shortest text that ParseNumber reads back as exactly `v` ("0.1", "52.2496",
// "1e-20"). `v` must be finite.
std::string FormatNumber(double v);
// `v` with at most `digits` significant digits, for messages ("4.65", "0.0152",
// "1.2e+03"); locale-independent. A value that is not finite is "inf", "-inf"
// or "nan", as printf's %g writes it: a message or report shows it as it is.
std::string FormatSignificant(double v, int digits = 3);

// A short, quoted, escaped excerpt of text from a file, for an error message:
// at most `max_chars` characters (then "..."), control and non-ASCII bytes as
// \xNN. An error quotes a file this way and never whole: the file may be
// /etc/passwd named by mistake, or by someone who wants to read it.
//   Excerpt("root:x:0:0:root:/root:/bin/bash\n...")  ->  'root:x:0:0:root:/root:/b...'
constexpr size_t kExcerptChars = 24;
std::string Excerpt(const std::string& text, size_t max_chars = kExcerptChars);

// Whether a key from a file may be shown in an error as it is: a name of
// letters, digits, '_' and '-', at most 40 characters. Anything else is shown
// by where it is, never by its text (issue 36: /etc/shadow's first line was
// echoed as an "unknown key").
bool IsPlainName(const std::string& key);
// FormatCsv written with WriteFileAtomically.
Status WriteCsv(const std::string& path, const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows);

}  // namespace hexcal

#include "core/csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::TestRng;
using ::hexcal::testing::Uniform;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Writes `text` to a fresh file and returns its path; the TempDir outlives it.
std::string WriteCsvFile(const TempDir& dir, const std::string& text) {
  const std::string path = dir.File("table.csv");
  WriteTextFile(path, text);
  return path;
}

std::string ReadCsvError(const std::string& path) { return testing::ErrorMessage(ReadCsv(path), path); }

// The error for a file holding `text`, after the file's path, which every
// message must start with.
std::string ErrorAfterPath(const std::string& text) {
  TempDir dir;
  const std::string path = WriteCsvFile(dir, text);
  const std::string message = ReadCsvError(path);
  if (message.rfind(path, 0) != 0) {
    ADD_FAILURE() << "'" << message << "' does not start with the path " << path;
    return message;
  }
  return message.substr(path.size());
}

TEST(CsvTest, ReadsHeaderRowsAndLineNumbers) {
  TempDir dir;
  const std::string path = WriteCsvFile(dir,
                                        "# poses for the left hand\n"
                                        "\n"
                                        " x , y ,z\n"
                                        "1,2,3\n"
                                        "   \n"
                                        "  # a comment after spaces\n"
                                        "4 ,\t5, 6\n");
  StatusOr<CsvTable> table = ReadCsv(path);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(table->source, path);
  EXPECT_EQ(table->header, (std::vector<std::string>{"x", "y", "z"}));
  ASSERT_EQ(table->rows.size(), 2u);
  EXPECT_EQ(table->rows[1], (std::vector<std::string>{"4", "5", "6"}));
  EXPECT_EQ(table->line_numbers, (std::vector<int>{4, 7}));
}

TEST(CsvTest, HandlesCrlfAndAByteOrderMark) {
  TempDir dir;
  const std::string path = WriteCsvFile(dir, "\xEF\xBB\xBFx,y\r\n1,2\r\n\r\n3,4\r\n");
  StatusOr<CsvTable> table = ReadCsv(path);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(table->header, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(table->rows, (std::vector<std::vector<std::string>>{{"1", "2"}, {"3", "4"}}));
  EXPECT_EQ(table->line_numbers, (std::vector<int>{2, 4}));
}

TEST(CsvTest, QuotedFieldsMayHoldCommasQuotesAndSpaces) {
  StatusOr<CsvTable> table = ParseCsv("name,note\n\"a,b\" , \"say \"\"hi\"\"\"\n\" padded \",\"\"\n", "mem");
  ASSERT_TRUE(table.ok()) << table.status().message();
  ASSERT_EQ(table->rows.size(), 2u);
  EXPECT_EQ(table->rows[0], (std::vector<std::string>{"a,b", "say \"hi\""}));
  EXPECT_EQ(table->rows[1], (std::vector<std::string>{" padded ", ""}));
}

TEST(CsvTest, MissingFileIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.File("nowhere.csv");
  EXPECT_EQ(ReadCsvError(path), path + ": no such file");
}

TEST(CsvTest, EmptyFileOrOnlyCommentsHasNoHeader) {
  for (const std::string text : {"", "\n\n", "# only a comment\n  \n"}) {
    EXPECT_EQ(ErrorAfterPath(text), ": no header line (the file is empty or holds only comments)");
  }
}

TEST(CsvTest, DuplicateHeaderNamesAreAnError) {
  EXPECT_EQ(ErrorAfterPath("# c\nx,y,x\n1,2,3\n"), ":2: duplicate column 'x' in header");
}

TEST(CsvTest, FirstLineOfNumbersIsAMissingHeader) {
  EXPECT_EQ(ErrorAfterPath("# poses\n0,0,53.5,0,0,0\n1,-1,53,2,-1,3\n"),
            ":2: no header: column 1 is the number '0', and the first line must name the columns");
}

TEST(CsvTest, UnnamedHeaderColumnIsAnError) { EXPECT_EQ(ErrorAfterPath("x,,z\n"), ":1: header column 2 has no name"); }

TEST(CsvTest, RowWithWrongColumnCountNamesLineAndCounts) {
  EXPECT_EQ(ErrorAfterPath("x,y,z,q1,q2,q3\n"
                           "0,0,53,0,0,0\n"
                           "\n"
                           "# next row lost a value\n"
                           "0,0,53,0,0,1\n"
                           "\n"
                           "0,0,53,0,0\n"),
            ":7: 5 columns, header has 6");
}

TEST(CsvTest, TrailingCommaCountsAsAnExtraColumn) {
  EXPECT_EQ(ErrorAfterPath("x,y\n1,2,\n"), ":2: 3 columns, header has 2");
}

TEST(CsvTest, BadQuotingNamesLineAndField) {
  EXPECT_EQ(ErrorAfterPath("x,y\n1,\"2\n"), ":2: field 2: quoted field has no closing quote");
  EXPECT_EQ(ErrorAfterPath("x,y\n\"1\"0,2\n"), ":2: field 1: text after the closing quote");
  EXPECT_THAT(ErrorAfterPath("x,y\n1,2\"\n"), StartsWith(":2: field 2: quote inside an unquoted"));
}

TEST(CsvTest, ParseNumberAcceptsFiniteDecimalNumbers) {
  const std::vector<std::pair<std::string, double>> cases = {{"1", 1.0},       {"-1.5e-3", -1.5e-3},
                                                             {"+2", 2.0},      {".5", 0.5},
                                                             {"5.", 5.0},      {"1E3", 1000.0},
                                                             {"-0", -0.0},     {"52.2496", 52.2496},
                                                             {"1e-20", 1e-20}, {"1.7976931348623157e308", DBL_MAX}};
  for (const auto& [text, expected] : cases) {
    StatusOr<double> value = ParseNumber(text);
    ASSERT_TRUE(value.ok()) << text << ": " << value.status().message();
    EXPECT_EQ(*value, expected) << text;
  }
}

TEST(CsvTest, ParseNumberRejectsAnythingButOneFiniteNumber) {
  EXPECT_EQ(ParseNumber("").status().message(), "expected a number, found nothing");
  for (const std::string text :
       {" ",  "abc",  "1.5x", "1 2", "1,5",  " 1",  "--1",  "+-1",      "++1",  "+",    "-",     ".",
        "e5", "0x10", "nan",  "NaN", "-nan", "inf", "-inf", "Infinity", ".inf", ".nan", "1e400", "-1e400"}) {
    StatusOr<double> value = ParseNumber(text);
    ASSERT_FALSE(value.ok()) << "'" << text << "' was accepted as " << *value;
    EXPECT_EQ(value.status().message(), "'" + text + "' is not a finite number");
  }
}

TEST(CsvTest, ColumnIndexNamesTheFileAndListsTheHeader) {
  StatusOr<CsvTable> table = ParseCsv("x,y,z,q1,q3\n", "poses.csv");
  ASSERT_TRUE(table.ok());
  EXPECT_EQ(*ColumnIndex(*table, "q3"), 4);
  StatusOr<int> missing = ColumnIndex(*table, "q2");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().message(), "poses.csv: missing column 'q2' (header: x,y,z,q1,q3)");
  // Column names are matched exactly.
  EXPECT_FALSE(ColumnIndex(*table, "X").ok());
}

TEST(CsvTest, NumberAtNamesFileLineAndColumn) {
  StatusOr<CsvTable> table = ParseCsv("x,y,z\n# c\n1,2,3\n4,5,abc\n7,8,\n", "poses.csv");
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(*NumberAt(*table, 0, 2), 3.0);
  EXPECT_EQ(NumberAt(*table, 1, 2).status().message(), "poses.csv:4: column 'z': 'abc' is not a finite number");
  EXPECT_EQ(NumberAt(*table, 2, 2).status().message(), "poses.csv:5: column 'z': expected a number, found nothing");
}

TEST(CsvTest, LoadPosesTakesColumnsInAnyOrderAndIgnoresExtras) {
  TempDir dir;
  const std::string path = WriteCsvFile(dir,
                                        "id,q3,q2,q1,z,y,x,comment\r\n"
                                        "p1,6,5,4,3,2,1,\"home, roughly\"\r\n"
                                        "# second pose\r\n"
                                        "p2,-6,-5,-4,-3,-2,-1.25,\r\n");
  StatusOr<std::vector<Vector6d>> poses = LoadPoses(path);
  ASSERT_TRUE(poses.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), 2u);
  EXPECT_EQ((*poses)[0], (Vector6d() << 1, 2, 3, 4, 5, 6).finished());
  EXPECT_EQ((*poses)[1], (Vector6d() << -1.25, -2, -3, -4, -5, -6).finished());
}

// Plain tables take a direct path (no quotes, no rows of strings): it must
// take the layouts the general reader forgives and read them as it does.
TEST(CsvTest, LoadPosesReadsPlainTablesAsTheGeneralReader) {
  TempDir dir;
  std::string text = "\xEF\xBB\xBF  q1 ,x,\ty,z,q2,q3,extra\r\n# a comment\n\n";
  for (int row = 0; row < 500; ++row) {
    for (int k = 0; k < 6; ++k) {
      const double v = Uniform(-1, 1) * std::pow(10.0, static_cast<int>(Uniform(-8, 8)));
      text += (k == 2 && v > 0 ? " +" : " ") + FormatNumber(v) + (k == 4 ? "\t," : ",");
    }
    text += row % 3 ? "\r\n" : "\n";
    if (row % 50 == 0) text += "   \n  # ruler\n";
  }
  const std::string path = WriteCsvFile(dir, text);
  ASSERT_TRUE(PlainSixColumns(text, {"x", "y", "z", "q1", "q2", "q3"}).has_value()) << "the fast path refused it";
  EXPECT_FALSE(PlainSixColumns("x,y,z,q1,q2,q3\n1,2,3,4,5,\"6\"\n", {"x", "y", "z", "q1", "q2", "q3"}));
  StatusOr<std::vector<Vector6d>> poses = LoadPoses(path);
  StatusOr<CsvTable> table = ReadCsv(path);
  ASSERT_TRUE(poses.ok() && table.ok()) << poses.status().message();
  ASSERT_EQ(poses->size(), table->rows.size());
  const char* names[6] = {"x", "y", "z", "q1", "q2", "q3"};
  for (size_t row = 0; row < table->rows.size(); ++row) {
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ((*poses)[row][k], *NumberAt(*table, row, *ColumnIndex(*table, names[k]))) << row << " " << k;
    }
  }
}

TEST(CsvTest, LoadPosesErrorsNameFileLineAndColumn) {
  TempDir dir;
  std::string path = WriteCsvFile(dir, "x,y,z,q1,q3\n0,0,50,0,0\n");
  EXPECT_EQ(LoadPoses(path).status().message(), path + ": missing column 'q2' (header: x,y,z,q1,q3)");

  path = WriteCsvFile(dir, "x,y,z,q1,q2,q3\n0,0,50,0,0,0\n0,0,nan,0,0,0\n");
  EXPECT_EQ(LoadPoses(path).status().message(), path + ":3: column 'z': 'nan' is not a finite number");

  path = WriteCsvFile(dir, "x,y,z,q1,q2,q3\n0,0,50,0,0,0\n0,0,50,0,0\n");
  EXPECT_EQ(LoadPoses(path).status().message(), path + ":3: 5 columns, header has 6");

  path = WriteCsvFile(dir, "x,y,z,q1,q2,q3,x\n0,0,50,0,0,0,0\n");
  EXPECT_EQ(LoadPoses(path).status().message(), path + ":1: duplicate column 'x' in header");

  path = WriteCsvFile(dir, "x,y,z,q1,q2,q3\n# nothing yet\n");
  EXPECT_EQ(LoadPoses(path).status().message(), path + ": no poses (the file has a header but no data rows)");

  path = dir.File("absent.csv");
  EXPECT_THAT(LoadPoses(path).status().message(), StartsWith(path + ":"));
}

TEST(CsvTest, LoadLegReadingsReadsL1ToL6) {
  TempDir dir;
  std::string path = WriteCsvFile(dir, "pose,L6,L5,L4,L3,L2,L1\n0,0.6,0.5,0.4,0.3,0.2,0.1\n");
  StatusOr<std::vector<Eigen::Matrix<double, 6, 1>>> legs = LoadLegReadings(path);
  ASSERT_TRUE(legs.ok()) << legs.status().message();
  ASSERT_EQ(legs->size(), 1u);
  EXPECT_EQ((*legs)[0], (Vector6d() << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6).finished());

  path = WriteCsvFile(dir, "L1,L2,L3,L5,L6\n1,2,3,5,6\n");
  EXPECT_EQ(LoadLegReadings(path).status().message(), path + ": missing column 'L4' (header: L1,L2,L3,L5,L6)");
  path = WriteCsvFile(dir, "L1,L2,L3,L4,L5,L6\n");
  EXPECT_EQ(LoadLegReadings(path).status().message(),
            path + ": no leg readings (the file has a header but no data rows)");
}

TEST(CsvTest, FormatNumberIsShortAndExact) {
  EXPECT_EQ(FormatNumber(0), "0");
  EXPECT_EQ(FormatNumber(-0.0), "-0");
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(52.2496), "52.2496");
  EXPECT_EQ(FormatNumber(-9.7), "-9.7");
  EXPECT_EQ(FormatNumber(345), "345");
  EXPECT_EQ(FormatNumber(20), "20");
  EXPECT_EQ(FormatNumber(-180), "-180");
  EXPECT_EQ(FormatNumber(1e6), "1000000");
  EXPECT_EQ(FormatNumber(1.5e16), "15000000000000000");
  EXPECT_EQ(FormatNumber(1e17), "1e+17");
  EXPECT_EQ(FormatNumber(1e22), "1e+22");
  EXPECT_EQ(FormatNumber(0.0001), "0.0001");
  EXPECT_EQ(FormatNumber(0.00001), "1e-05");
  EXPECT_EQ(FormatNumber(1e-20), "1e-20");
  EXPECT_EQ(FormatNumber(0.1 + 0.2), "0.30000000000000004");
}

TEST(CsvTest, FormatSignificantIsPrintfsG) {
  EXPECT_EQ(FormatSignificant(0.0041321), "0.00413");
  EXPECT_EQ(FormatSignificant(1234.5), "1.23e+03");
  EXPECT_EQ(FormatSignificant(52.2496, 6), "52.2496");
  EXPECT_EQ(FormatSignificant(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(FormatSignificant(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(FormatSignificant(std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(CsvTest, FormatNumberRoundTripsEveryFiniteDouble) {
  std::vector<double> values = {
      1.0 / 3.0,   M_PI, -2.0 / 3.0 * 1e-300, DBL_MAX, -DBL_MAX, DBL_MIN, std::numeric_limits<double>::denorm_min(),
      123456789.0, 1e22, 9007199254740993.0};
  // Random bit patterns cover every exponent, not just the values people type.
  std::uniform_int_distribution<uint64_t> bits;
  while (values.size() < 20000) {
    const uint64_t pattern = bits(TestRng());
    double v;
    std::memcpy(&v, &pattern, sizeof v);
    if (std::isfinite(v)) values.push_back(v);
  }
  for (double v : values) {
    const std::string text = FormatNumber(v);
    StatusOr<double> parsed = ParseNumber(text);
    ASSERT_TRUE(parsed.ok()) << text << ": " << parsed.status().message();
    ASSERT_EQ(std::memcmp(&*parsed, &v, sizeof v), 0) << text;
    ASSERT_LE(text.size(), 24u) << text;
  }
}

TEST(CsvTest, WriteCsvThenReadCsvGivesTheSameTable) {
  TempDir dir;
  const std::string path = dir.File("out.csv");
  const std::vector<std::string> header = {"name", "x", "note"};
  const std::vector<std::vector<std::string>> rows = {{"#1", FormatNumber(0.1 + 0.2), "a,b"},
                                                      {" padded", FormatNumber(-1e-300), "say \"hi\""},
                                                      {"", FormatNumber(7), ""}};
  ASSERT_TRUE(WriteCsv(path, header, rows).ok());
  StatusOr<CsvTable> table = ReadCsv(path);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(table->header, header);
  EXPECT_EQ(table->rows, rows);
  EXPECT_EQ(*NumberAt(*table, 0, 1), 0.1 + 0.2);
}

TEST(CsvTest, FormatCsvQuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(FormatCsv({"x", "y"}, {{"1", "2"}, {"a,b", ""}}), "x,y\n1,2\n\"a,b\",\"\"\n");
}

// Issue 13: an error quotes a file at most as a short, escaped excerpt.
TEST(CsvTest, ExcerptIsShortQuotedAndEscaped) {
  EXPECT_EQ(Excerpt("nan"), "'nan'");
  EXPECT_EQ(Excerpt("root:x:0:0:root:/root:/bin/bash\nsecret"), "'root:x:0:0:root:/root:/b...'");
  EXPECT_EQ(Excerpt(std::string("a\tb\x01\xff\\", 6)), "'a\\x09b\\x01\\xff\\x5c'");
}

TEST(CsvTest, MissingColumnQuotesOnlyTheStartOfTheFirstLine) {
  TempDir dir;
  const std::string path = dir.File("passwd.csv");
  WriteTextFile(path, "root:x:0:0:root:/root:/bin/bash:/usr/sbin/nologin:SECRET,daemon:x:1:1\n1,2\n");
  StatusOr<std::vector<Vector6d>> poses = LoadPoses(path);
  ASSERT_FALSE(poses.ok());
  EXPECT_THAT(poses.status().message(),
              HasSubstr("missing column 'x' (header: root:x:0:0:root:/root:/b...)"));
  EXPECT_THAT(poses.status().message(), ::testing::Not(HasSubstr("SECRET")));
}

}  // namespace
}  // namespace hexcal

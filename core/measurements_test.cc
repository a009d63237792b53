// The measurements file: columns in any order, extra columns ignored, every
// bad cell or missing column named with file, line and column, and an exact
// save/load round trip.
#include "core/measurements.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;

std::string ParseError(const std::string& text) {
  return testing::ErrorMessage(ParseMeasurements(text, "m.csv"), text);
}

TEST(Measurements, ReadsColumnsInAnyOrderAndIgnoresOthers) {
  StatusOr<std::vector<Measurement>> rows = ParseMeasurements(
      "# two measurements\n"
      "L6,note,q3,q2,q1,z,y,x,L1,L2,L3,L4,L5,feasible\n"
      "6,first,0.3,0.2,0.1,53,2,1,1.5,2,2.5,3,3.5,1\n"
      "0.6,,3,2,1,54,-2,-1,0.1,0.2,0.3,0.4,0.5,0\n",
      "m.csv");
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);
  Vector6d pose;
  pose << 1, 2, 53, 0.1, 0.2, 0.3;
  LegReadings legs;
  legs << 1.5, 2, 2.5, 3, 3.5, 6;
  EXPECT_EQ((*rows)[0].pose, pose);
  EXPECT_EQ((*rows)[0].legs, legs);
  EXPECT_EQ((*rows)[1].legs[5], 0.6);
  EXPECT_EQ((*rows)[1].pose[0], -1);
}

TEST(Measurements, NamesTheMissingColumn) {
  const std::string message = ParseError("x,y,z,q1,q2,q3,L1,L2,L3,L5,L6\n0,0,53,0,0,0,1,1,1,1,1\n");
  EXPECT_THAT(message, HasSubstr("m.csv: missing column 'L4'"));
}

TEST(Measurements, NamesLineAndColumnOfABadCell) {
  const std::string message = ParseError(
      "x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6\n"
      "0,0,53,0,0,0,1,1,1,1,1,1\n"
      "0,0,53,0,nan,0,1,1,1,1,1,1\n");
  EXPECT_THAT(message, HasSubstr("m.csv:3: column 'q2': 'nan' is not a finite number"));
  EXPECT_THAT(ParseError("x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6\n0,0,53,0,0,0,1,1,1,1,1\n"),
              HasSubstr("m.csv:2: 11 columns, header has 12"));
}

TEST(Measurements, RejectsAHeaderWithoutRows) {
  EXPECT_THAT(ParseError("x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6\n"), HasSubstr("no measurements"));
}

TEST(Measurements, SaveAndLoadGiveBackTheSameDoubles) {
  TempDir dir;
  std::vector<Measurement> rows(5);
  for (Measurement& m : rows) {
    for (int k = 0; k < 6; ++k) m.pose[k] = Uniform(-10, 60);
    for (int i = 0; i < kNumLegs; ++i) m.legs[i] = Uniform(0, 3.5);
  }
  ASSERT_TRUE(SaveMeasurements(dir.File("m.csv"), rows).ok());
  StatusOr<std::vector<Measurement>> loaded = LoadMeasurements(dir.File("m.csv"));
  ASSERT_TRUE(loaded.ok()) << loaded.status().message();
  ASSERT_EQ(loaded->size(), rows.size());
  for (size_t j = 0; j < rows.size(); ++j) {
    EXPECT_EQ((*loaded)[j].pose, rows[j].pose);
    EXPECT_EQ((*loaded)[j].legs, rows[j].legs);
  }
}

TEST(Measurements, MissingFileIsAnError) {
  StatusOr<std::vector<Measurement>> rows = LoadMeasurements("/no/such/dir/m.csv");
  ASSERT_FALSE(rows.ok());
  EXPECT_THAT(rows.status().message(), HasSubstr("/no/such/dir/m.csv"));
}

}  // namespace
}  // namespace hexcal

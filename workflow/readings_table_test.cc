// The readings table the GUI edits: legs.csv's rows and a blank row for each
// image without readings (session/readings_table.h).
#include "session/readings_table.h"

#include <gtest/gtest.h>

#include "core/session.h"
#include "tests/test_support.h"
#include "workflow/session_edits.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

TEST(ReadingsTable, ImagesWithoutLegsCsvGiveBlankRowsToTypeInto) {
  TempDir dir;
  const std::string s = NewCameraSession(dir);
  WriteTextFile(s + "/images/b.png", "b");
  WriteTextFile(s + "/images/a.png", "a");
  EXPECT_FALSE(LoadSessionLegs(s).ok());  // the session's rows do not load yet...
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 2u);  // ...but the table has a row for each image
  EXPECT_EQ((*rows)[0].image, "a.png");
  EXPECT_FALSE((*rows)[0].recorded);
  EXPECT_TRUE((*rows)[0].image_present);
  EXPECT_FALSE((*rows)[0].legs[0].has_value());

  // Six readings typed for a.png: its row enters legs.csv, b.png stays blank.
  LegsRow typed;
  typed.image = "a.png";
  typed.legs << 50, 51, 52, 53, 54, 55;
  ASSERT_TRUE(ApplyLegsEdit(s, LegsEdit::SetRow(typed)).status.ok());
  rows = ReadReadingsTable(s);
  ASSERT_TRUE(rows.ok());
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_TRUE((*rows)[0].recorded);
  EXPECT_EQ((*rows)[0].legs[2], 52);
  EXPECT_FALSE((*rows)[1].recorded);
}

TEST(ReadingsTable, RowsWhoseImageIsMissingOrCellIsNotANumberAreShown) {
  TempDir dir;
  const std::string s = NewCameraSession(dir);
  WriteTextFile(s + "/legs.csv", "image,L1,L2,L3,L4,L5,L6,holdout\ngone.png,50,x,52,53,54,55,1\n");
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(s);
  ASSERT_TRUE(rows.ok()) << rows.status().message();
  ASSERT_EQ(rows->size(), 1u);
  EXPECT_TRUE((*rows)[0].recorded);
  EXPECT_FALSE((*rows)[0].image_present);
  EXPECT_EQ((*rows)[0].legs[0], 50);
  EXPECT_FALSE((*rows)[0].legs[1].has_value());
  EXPECT_TRUE((*rows)[0].holdout);
  WriteTextFile(s + "/legs.csv", "image,L1,L2\n");
  EXPECT_FALSE(ReadReadingsTable(s).ok());  // a column missing
}

TEST(ReadingsTable, APastedLineGivesSixReadings) {
  using Readings = std::array<double, kNumLegs>;
  EXPECT_EQ(ParseReadingsLine("50\t51\t52\t53\t54\t55"), (Readings{50, 51, 52, 53, 54, 55}));
  EXPECT_EQ(ParseReadingsLine("pose_0001.png, 50.5, 51, 52, 53, 54, 55"), (Readings{50.5, 51, 52, 53, 54, 55}));
  EXPECT_EQ(ParseReadingsLine("50 51 52 53 54 55 1"), (Readings{50, 51, 52, 53, 54, 55}));  // and a holdout
  EXPECT_FALSE(ParseReadingsLine("50 51 52 53 54").has_value());
  EXPECT_FALSE(ParseReadingsLine("50 51 52 53 54 55 56 57").has_value());
  EXPECT_FALSE(ParseReadingsLine("50 51 52 mm 53 54 55").has_value());
  EXPECT_FALSE(ParseReadingsLine("").has_value());
}

}  // namespace
}  // namespace hexcal::workflow

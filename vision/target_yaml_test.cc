// Target files with an id matrix or a tag list: parsing, errors, round trip.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"
#include "vision/target.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string ParseError(const std::string& yaml) { return testing::ErrorMessage(ParseTargetYaml(yaml, "t.yaml"), yaml); }

const char* kCommon = "tag_size: 40\ntag_spacing: 0.25\nlength_unit: mm\n";
// Two rows of three as printed; the bottom-left cell has no tag.
const char* kMatrix = "ids:\n  - [17, 200, 5]\n  - [-1, 93, 41]\n";
const char* kList =
    "tag_size: 30\nlength_unit: mm\ntags:\n  - {id: 17, x: 0, y: 0}\n"
    "  - {id: 200, x: 100, y: -20}\n  - {id: 5, x: 40, y: 60}\n";

TEST(TargetIdMatrixTest, ParsesRowsAsPrintedTopRowFirst) {
  StatusOr<Target> target = ParseTargetYaml(std::string(kCommon) + kMatrix, "t.yaml");
  ASSERT_TRUE(target.ok()) << target.status().message();
  EXPECT_EQ(target->Layout(), TargetLayout::kIdMatrix);
  EXPECT_EQ(target->rows, 2);
  EXPECT_EQ(target->cols, 3);
  EXPECT_EQ(target->NumTags(), 5);
  // Indices from the bottom-left, along a row, then upwards; the hole skipped.
  EXPECT_THAT(target->TagIds(), ElementsAre(93, 41, 17, 200, 5));
  EXPECT_EQ(*target->IndexOf(17), 2);
  EXPECT_FALSE(target->IndexOf(0).has_value());
  const double pitch = 50;  // 40 · 1.25
  EXPECT_TRUE(testing::MatrixNear(target->TagOrigin(*target->IndexOf(93)), Eigen::Vector2d(pitch, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(target->TagOrigin(*target->IndexOf(5)), Eigen::Vector2d(2 * pitch, pitch), 0));
  // The bounding box of the black squares is the whole grid: the top row fills it.
  EXPECT_TRUE(testing::MatrixNear(target->TagsMin(), Eigen::Vector2d(0, 0), 0));
  EXPECT_DOUBLE_EQ(target->Width(), 140);
  EXPECT_DOUBLE_EQ(target->Height(), 90);
  EXPECT_EQ(DescribeTarget(*target),
            "5 tag36h11 tags (id matrix 2 x 3), tag 40 mm, gap 10 mm (spacing 0.25), ids 5-200");
}

TEST(TargetIdMatrixTest, CornersEqualTheGridsForTheSameLayout) {
  StatusOr<Target> grid = ParseTargetYaml(std::string(kCommon) + "rows: 2\ncols: 3\nfirst_id: 10\n", "g");
  StatusOr<Target> matrix =
      ParseTargetYaml(std::string(kCommon) + "rows: 2\ncols: 3\nids:\n  - [13, 14, 15]\n  - [10, 11, 12]\n", "m");
  ASSERT_TRUE(grid.ok() && matrix.ok()) << matrix.status().message();
  ASSERT_EQ(matrix->NumTags(), grid->NumTags());
  for (int index = 0; index < grid->NumTags(); ++index) {
    EXPECT_EQ(matrix->TagId(index), grid->TagId(index));
    const auto a = grid->TagCorners(grid->TagId(index)), b = matrix->TagCorners(grid->TagId(index));
    for (size_t k = 0; k < 4; ++k) EXPECT_TRUE(testing::MatrixNear(a[k], b[k], 0)) << index << " " << k;
  }
  EXPECT_EQ(matrix->Width(), grid->Width());
  EXPECT_EQ(matrix->Height(), grid->Height());
  EXPECT_EQ(matrix->margin, grid->margin);
}

TEST(TargetIdMatrixTest, ErrorsNameTheKey) {
  const std::string common = kCommon;
  EXPECT_THAT(ParseError(common + "ids:\n  - [1, 2, 3, 4, 5, 6]\n  - [7, 8, 9, 10, 11]\n"),
              HasSubstr("target file 't.yaml': ids: row 2 has 5 entries, row 1 has 6"));
  EXPECT_THAT(ParseError(common + "first_id: 3\n" + kMatrix),
              HasSubstr("target file 't.yaml': ids: given together with first_id"));
  EXPECT_THAT(ParseError(common + "rows: 3\n" + kMatrix), HasSubstr("rows: 3 disagrees with ids (2 rows)"));
  EXPECT_THAT(ParseError(common + "tagCols: 4\n" + kMatrix),
              HasSubstr("tagCols: 4 disagrees with ids (3 entries in a row)"));
  EXPECT_THAT(ParseError(common + "ids:\n  - [1, 2]\n  - [3, 1]\n"),
              HasSubstr("ids: id 1 appears twice (row 1, column 1 and row 2, column 2)"));
  EXPECT_THAT(ParseError(common + "ids:\n  - [1, 2]\n  - [3, 587]\n"),
              HasSubstr("ids: row 2, column 2: 587 is not a tag of tag36h11 (0 to 586, or -1 for no tag)"));
  EXPECT_THAT(ParseError(common + "ids:\n  - [1, -2]\n"), HasSubstr("ids: row 1, column 2: -2 is not a tag"));
  EXPECT_THAT(ParseError(common + "ids:\n  - [1, 2.5]\n"),
              HasSubstr("ids: row 1, column 2: expected a whole number, found '2.5'"));
  EXPECT_THAT(ParseError(common + "ids:\n  - [-1, -1]\n"), HasSubstr("ids: no tag on the board"));
  EXPECT_THAT(ParseError(common + "ids: 7\n"), HasSubstr("ids: expected a list of rows as printed"));
  EXPECT_THAT(ParseError(common + "ids:\n  - 7\n"), HasSubstr("ids: row 1: expected a list"));
  EXPECT_THAT(ParseError("tag_size: 40\ntag_spacing: 0.1\nlength_unit: mm\n" + std::string(kMatrix)),
              HasSubstr("tag_spacing: 0.1 leaves less than one bit cell"));
}

TEST(TargetTagListTest, ParsesPositionsInTheTargetFrame) {
  StatusOr<Target> target = ParseTargetYaml(kList, "t.yaml");
  ASSERT_TRUE(target.ok()) << target.status().message();
  EXPECT_EQ(target->Layout(), TargetLayout::kTagList);
  EXPECT_THAT(target->TagIds(), ElementsAre(17, 200, 5));
  const std::array<Eigen::Vector3d, 4> corners = target->TagCorners(200);
  EXPECT_TRUE(testing::MatrixNear(corners[0], Eigen::Vector3d(100, -20, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(corners[2], Eigen::Vector3d(130, 10, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(target->TagsMin(), Eigen::Vector2d(0, -20), 0));
  EXPECT_DOUBLE_EQ(target->Width(), 130);
  EXPECT_DOUBLE_EQ(target->Height(), 110);
  EXPECT_DOUBLE_EQ(target->margin, 9);  // as a grid of Kalibr's spacing 0.3
  EXPECT_EQ(DescribeTarget(*target), "3 tag36h11 tags (tag list), tag 30 mm, 130 x 110 mm, ids 5-200");
}

TEST(TargetTagListTest, ErrorsNameTheKey) {
  const std::string head = "tag_size: 30\nlength_unit: mm\ntags:\n";
  EXPECT_THAT(ParseError(head + "  - {id: 7, x: 0, y: 0}\n  - {id: 7, x: 50, y: 0}\n"),
              HasSubstr("target file 't.yaml': tags: id 7 appears twice (entries 1 and 2)"));
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0, y: 0}\n  - {id: 2, x: 50, y: 0}\n  - {id: 3, x: 200, y: 0}\n"
                                "  - {id: 4, x: 210, y: 20}\n"),
              HasSubstr("tags: tags 3 and 4 overlap"));
  // One bit cell is 30/8 = 3.75: 3 mm of white is too little, 3.75 enough.
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0, y: 0}\n  - {id: 2, x: 10, y: 33}\n"),
              HasSubstr("tags: tags 1 and 2 are 3 apart, less than one bit cell (3.75) of white"));
  EXPECT_TRUE(ParseTargetYaml(head + "  - {id: 1, x: 0, y: 0}\n  - {id: 2, x: 10, y: 33.75}\n", "t").ok());
  EXPECT_THAT(ParseError(head + "  - {id: 600, x: 0, y: 0}\n"), HasSubstr("tags: id 600 is not a tag of tag36h11"));
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0}\n"), HasSubstr("tags: entry 1: y missing"));
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0, y: 0, z: 1}\n"), HasSubstr("tags: entry 1: unknown key 'z'"));
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0, y: nan}\n"), HasSubstr("tags: entry 1: y: expected a finite"));
  EXPECT_THAT(ParseError(head + "  - [1, 0, 0]\n"), HasSubstr("tags: entry 1: expected a list of {id"));
  EXPECT_THAT(ParseError(head + "  - {id: 1, x: 0, y: 0}\nmargin: 2\n"), HasSubstr("margin: 2 is less than one"));
  EXPECT_THAT(ParseError("rows: 2\n" + head + "  - {id: 1, x: 0, y: 0}\n"),
              HasSubstr("tags: given together with rows; a tag list places each tag itself"));
  EXPECT_THAT(ParseError("tagSpacing: 0.3\n" + head + "  - {id: 1, x: 0, y: 0}\n"),
              HasSubstr("tags: given together with tagSpacing"));
  EXPECT_THAT(ParseError(std::string(kMatrix) + head + "  - {id: 1, x: 0, y: 0}\n"),
              HasSubstr("tags: given together with ids"));
}

TEST(TargetLayoutTest, YamlRoundTripIsExactForEveryLayout) {
  Target matrix;
  matrix.tag_size = 0.1 + 0.2;
  matrix.tag_spacing = 1.0 / 3;
  matrix.length_unit = LengthUnit::kCentimetre;
  matrix.margin = 0.11;
  matrix.SetIdMatrix({{3, -1, 212}, {40, 41, 7}});
  Target list;
  list.border_bits = 2;
  list.margin = 7.5;
  list.SetTagList({{9, 0.1, 1.0 / 3}, {4, 50.25, -60}, {586, -40, 0}});
  for (const Target& target : {DefaultTarget(), matrix, list}) {
    StatusOr<Target> back = ParseTargetYaml(TargetToYaml(target), "round-trip");
    ASSERT_TRUE(back.ok()) << back.status().message() << "\n" << TargetToYaml(target);
    EXPECT_EQ(back->Layout(), target.Layout());
    EXPECT_EQ(back->IdMatrix(), target.IdMatrix());
    EXPECT_EQ(back->TagIds(), target.TagIds());
    for (int index = 0; index < target.NumTags(); ++index) {
      EXPECT_EQ(back->TagOrigin(index), target.TagOrigin(index)) << index;
    }
    EXPECT_EQ(back->rows, target.rows);
    EXPECT_EQ(back->cols, target.cols);
    EXPECT_EQ(back->tag_size, target.tag_size);
    EXPECT_EQ(back->tag_spacing, target.tag_spacing);
    EXPECT_EQ(back->first_id, target.first_id);
    EXPECT_EQ(back->margin, target.margin);
    EXPECT_EQ(back->border_bits, target.border_bits);
    EXPECT_EQ(back->length_unit, target.length_unit);
    EXPECT_EQ(TargetToYaml(*back), TargetToYaml(target));
  }
  EXPECT_THAT(TargetToYaml(matrix), HasSubstr("ids:"));
  EXPECT_THAT(TargetToYaml(matrix), ::testing::Not(HasSubstr("first_id")));
  EXPECT_THAT(TargetToYaml(list), HasSubstr("  - {id: 4, x: 50.25, y: -60}\n"));
}

TEST(TargetLayoutTest, MosaicExampleLoads) {
  StatusOr<Target> target = LoadTarget((SourceDir() / "resources/targets/mosaic-example.yaml").string());
  ASSERT_TRUE(target.ok()) << target.status().message();
  EXPECT_EQ(target->Layout(), TargetLayout::kIdMatrix);
  EXPECT_GT(target->NumTags(), 0);
}

}  // namespace
}  // namespace hexcal

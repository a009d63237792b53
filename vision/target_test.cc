#include "vision/target.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_support.h"
#include "vision/tag_family.h"
#include "vision/target_coverage.h"

namespace hexcal {
namespace {

using ::hexcal::testing::SourceDir;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

std::string ParseError(const std::string& yaml) { return testing::ErrorMessage(ParseTargetYaml(yaml, "t.yaml"), yaml); }

const char* kMinimal = "rows: 2\ncols: 3\ntag_size: 40\ntag_spacing: 0.25\nlength_unit: mm\n";

TEST(TargetTest, DefaultResourceFileIsTheBuiltInTarget) {
  StatusOr<Target> file = LoadTarget((SourceDir() / "resources/targets/aprilgrid-6x6.yaml").string());
  ASSERT_TRUE(file.ok()) << file.status().message();
  StatusOr<Target> builtin = LoadTarget(kDefaultTargetName);
  ASSERT_TRUE(builtin.ok());
  for (const Target* t : {&*file, &*builtin}) {
    EXPECT_EQ(t->family, "tag36h11");
    EXPECT_EQ(t->rows, 6);
    EXPECT_EQ(t->cols, 6);
    EXPECT_EQ(t->tag_size, 30);
    EXPECT_EQ(t->tag_spacing, 0.3);
    EXPECT_EQ(t->first_id, 0);
    EXPECT_EQ(t->length_unit, LengthUnit::kMillimetre);
    EXPECT_EQ(t->margin, 9);
  }
  EXPECT_NEAR(builtin->Width(), 225, 1e-12);
}

TEST(TargetTest, ReadsKalibrAprilgridInMetres) {
  StatusOr<Target> target = LoadTarget((SourceDir() / "tests/data/targets/kalibr_aprilgrid.yaml").string());
  ASSERT_TRUE(target.ok()) << target.status().message();
  EXPECT_EQ(target->rows, 6);
  EXPECT_EQ(target->cols, 6);
  EXPECT_EQ(target->tag_size, 0.088);
  EXPECT_EQ(target->length_unit, LengthUnit::kMetre);
  // Kalibr: tagSpacing is the gap as a fraction of tagSize.
  EXPECT_NEAR(target->Gap(), 0.0264, 1e-15);
  EXPECT_NEAR(target->Pitch(), 0.1144, 1e-15);
  EXPECT_NEAR(target->margin, 0.0264, 1e-15);  // default: the gap (more than two bit cells)
  EXPECT_EQ(target->border_bits, 2);            // as Kalibr prints its aprilgrid
  EXPECT_EQ(target->WidthAtBorder(), 10);
}

TEST(TargetTest, BorderBitsDefaultByKeyNamesAndAreChecked) {
  EXPECT_EQ(DefaultTarget().border_bits, 1);
  EXPECT_EQ(DefaultTarget().WidthAtBorder(), 8);
  const std::string kalibr = "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.3\n";
  EXPECT_EQ(ParseTargetYaml(kalibr + "border_bits: 1\n", "k").value().border_bits, 1);
  const StatusOr<Target> three = ParseTargetYaml(kalibr + "border_bits: 3\n", "k");
  EXPECT_THAT(three.status().message(), HasSubstr("border_bits: must be 1 (AprilTag's tags) or 2"));
  // Two border cells need two cells of white: 0.15 of a 10-cell tag is 1.5.
  const StatusOr<Target> tight = ParseTargetYaml(
      "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.15\n", "k");
  EXPECT_THAT(tight.status().message(), HasSubstr("leaves less than two bit cells"));
}

TEST(TargetTest, CornersFollowTheTargetFrameAndAprilTagOrder) {
  StatusOr<Target> target = ParseTargetYaml(std::string(kMinimal) + "first_id: 10\n", "t.yaml");
  ASSERT_TRUE(target.ok()) << target.status().message();
  const std::array<Eigen::Vector3d, 4> first = target->TagCorners(10);
  // Bottom-left, bottom-right, top-right, top-left of the black square.
  EXPECT_TRUE(testing::MatrixNear(first[0], Eigen::Vector3d(0, 0, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(first[1], Eigen::Vector3d(40, 0, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(first[2], Eigen::Vector3d(40, 40, 0), 0));
  EXPECT_TRUE(testing::MatrixNear(first[3], Eigen::Vector3d(0, 40, 0), 0));
  // Id 14 = index 4: row 1 (up), column 1; pitch 40 * 1.25 = 50.
  const std::array<Eigen::Vector3d, 4> up = target->TagCorners(14);
  EXPECT_TRUE(testing::MatrixNear(up[0], Eigen::Vector3d(50, 50, 0), 1e-12));
  EXPECT_FALSE(target->IndexOf(9).has_value());
  EXPECT_FALSE(target->IndexOf(16).has_value());
  EXPECT_EQ(*target->IndexOf(15), 5);
}

TEST(TargetTest, YamlRoundTripIsExact) {
  Target target;
  target.tag_size = 0.1 + 0.2;
  target.tag_spacing = 1.0 / 3;
  target.margin = 0.07;
  target.length_unit = LengthUnit::kCentimetre;
  target.rows = 4;
  target.first_id = 100;
  target.border_bits = 2;
  StatusOr<Target> back = ParseTargetYaml(TargetToYaml(target), "round-trip");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->tag_size, target.tag_size);
  EXPECT_EQ(back->tag_spacing, target.tag_spacing);
  EXPECT_EQ(back->margin, target.margin);
  EXPECT_EQ(back->length_unit, target.length_unit);
  EXPECT_EQ(back->rows, 4);
  EXPECT_EQ(back->first_id, 100);
  EXPECT_EQ(back->border_bits, 2);
}

TEST(TargetTest, ErrorsNameTheFileTheKeyAndTheProblem) {
  EXPECT_THAT(ParseError("rows: 2\ncols: 3\ntag_size: 40\ntag_spacing: 0.3\n"),
              HasSubstr("target file 't.yaml': length_unit: missing"));
  EXPECT_THAT(ParseError(std::string(kMinimal) + "colour: red\n"), HasSubstr("colour: unknown key"));
  EXPECT_THAT(ParseError(std::string(kMinimal) + "tagRows: 2\n"), HasSubstr("tagRows: given together with rows"));
  EXPECT_THAT(ParseError("rows: 2.5\ncols: 3\ntag_size: 40\ntag_spacing: 0.3\nlength_unit: mm\n"),
              HasSubstr("rows: expected a whole number, found 2.5"));
  EXPECT_THAT(ParseError("rows: 2\ncols: 3\ntag_size: -4\ntag_spacing: 0.3\nlength_unit: mm\n"),
              HasSubstr("tag_size: must be a positive length"));
  EXPECT_THAT(ParseError("rows: 2\ncols: 3\ntag_size: 40\ntag_spacing: 0.1\nlength_unit: mm\n"),
              HasSubstr("tag_spacing: 0.1 leaves less than one bit cell"));
  EXPECT_THAT(ParseError(std::string(kMinimal) + "first_id: 585\n"),
              HasSubstr("first_id: ids 585 to 590 exceed the 587 tags of tag36h11"));
  EXPECT_THAT(ParseError(std::string(kMinimal) + "family: tag36h10\n"),
              HasSubstr("family: 'tag36h10' is not supported; expected one of tag36h11, tag25h9, tag16h5"));
  EXPECT_THAT(ParseError("rows: 2\ncols: 3\ntag_size: nan\ntag_spacing: 0.3\nlength_unit: mm\n"),
              HasSubstr("tag_size: 'nan' is not a finite number"));
  EXPECT_THAT(ParseError(std::string(kMinimal) + "margin: 1\n"), HasSubstr("margin: 1 is less than one bit cell"));
  EXPECT_THAT(ParseError("cols: 3\ntag_size: 40\ntag_spacing: 0.3\nlength_unit: mm\n"),
              HasSubstr("rows: missing (or tagRows)"));
  EXPECT_THAT(ParseError("target_type: checkerboard\n"), HasSubstr("target_type: only 'aprilgrid'"));
  EXPECT_THAT(ParseError("rows: [2\n"), HasSubstr("YAML syntax error at line"));
  EXPECT_THAT(ParseError("- 1\n- 2\n"), HasSubstr("top level: expected a mapping"));
}

TEST(TargetTest, MissingFileNamesTheBuiltIn) {
  StatusOr<Target> target = LoadTarget("no-such-target.yaml");
  ASSERT_FALSE(target.ok());
  EXPECT_THAT(target.status().message(), HasSubstr("no-such-target.yaml: no such file"));
  EXPECT_THAT(target.status().message(), HasSubstr("aprilgrid-6x6"));
}

TEST(TagFamilyTest, Tag36h11CellsComeFromTheLibrary) {
  const std::optional<TagFamilyInfo> info = FindTagFamily("tag36h11");
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->width_at_border, 8);
  EXPECT_EQ(info->total_width, 10);
  EXPECT_EQ(info->num_codes, 587);
  const std::vector<TagCells> cells = TagCellsOf("tag36h11", 0, 2);
  // Tag 0 as apriltag_to_image draws it (row 0 at the top; # black).
  const char* kTag0[10] = {"..........", ".########.", ".#..#.#.#.", ".##...#.#.", ".##..####.",
                           ".#.#.####.", ".##.#..##.", ".####.###.", ".########.", ".........."};
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 10; ++col)
      EXPECT_EQ(cells[0].IsBlack(row, col), kTag0[row][col] == '#') << row << "," << col;
  }
  EXPECT_NE(cells[0].black, cells[1].black);
  EXPECT_FALSE(FindTagFamily("tagCircle21h7").has_value());
}

TEST(TargetPatternTest, CoverageIsExactArea) {
  const Target target = DefaultTarget();
  const TargetPattern pattern(target);
  const double cell = target.tag_size / 8;
  auto square = [](double x, double y, double size) {
    return std::array<Eigen::Vector2d, 4>{Eigen::Vector2d(x, y), Eigen::Vector2d(x + size, y),
                                          Eigen::Vector2d(x + size, y + size), Eigen::Vector2d(x, y + size)};
  };
  // Inside the black border of tag 0 (bottom-left cell).
  TargetPattern::Coverage c = pattern.Cover(square(0.1 * cell, 0.1 * cell, 0.5 * cell));
  EXPECT_EQ(c.sheet, 1);
  EXPECT_NEAR(c.black, 1, 1e-12);
  // Straddling the left edge of tag 0: a quarter outside.
  c = pattern.Cover(square(-0.25 * cell, 2 * cell, 0.5 * cell));
  EXPECT_NEAR(c.black, 0.5, 1e-12);
  // Straddling the sheet's edge: half off the sheet.
  c = pattern.Cover(square(-target.margin - 0.5, 10, 1));
  EXPECT_NEAR(c.sheet, 0.5, 1e-12);
  EXPECT_NEAR(c.black, 0, 1e-12);
  // A rotated square against a Monte Carlo estimate over several cells.
  std::array<Eigen::Vector2d, 4> quad;
  const Eigen::Vector2d centre(3.3 * cell, 4.1 * cell);
  for (int k = 0; k < 4; ++k) {
    const double a = 0.4 + k * kPi / 2;
    quad[static_cast<size_t>(k)] = centre + 1.7 * cell * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  c = pattern.Cover(quad);
  int black = 0, inside = 0;
  for (int i = 0; i < 400; ++i) {
    for (int j = 0; j < 400; ++j) {
      const Eigen::Vector2d p =
          centre + Eigen::Vector2d(-2 * cell + 4 * cell * (i + 0.5) / 400, -2 * cell + 4 * cell * (j + 0.5) / 400);
      const Eigen::Vector2d d = p - centre;
      const Eigen::Vector2d u(std::cos(0.4), std::sin(0.4)), v(-std::sin(0.4), std::cos(0.4));
      if (std::abs(d.dot(u)) + std::abs(d.dot(v)) > 1.7 * cell) continue;  // outside the rotated square
      ++inside;
      black += pattern.IsBlackAt(p);
    }
  }
  EXPECT_NEAR(c.black, static_cast<double>(black) / inside, 0.01);
  EXPECT_GT(c.black, 0.05);
  EXPECT_LT(c.black, 0.95);
}

}  // namespace
}  // namespace hexcal

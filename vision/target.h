// The calibration target: AprilTags on a flat sheet, read from YAML. Its tag
// ids make it asymmetric, so every detected tag says which corners of the
// board it shows. Three layouts:
//
// A grid (an "aprilgrid" in Kalibr's terms), ids first_id, first_id + 1, ...
//   family: tag36h11      # tag36h11 | tag25h9 | tag16h5
//   rows: 6               # or tagRows (Kalibr)
//   cols: 6               # or tagCols
//   tag_size: 30          # or tagSize: edge of a tag's black square, length unit
//   tag_spacing: 0.3      # or tagSpacing: gap between tags / tag_size (Kalibr's ratio)
//   first_id: 0           # id of the bottom-left tag; ids grow along a row, then upwards
//   length_unit: mm       # mm | cm | m; Kalibr files (tagSize ...) default to m
//   margin: 9             # optional: white sheet beyond the outer tags, length unit
//   border_bits: 1        # black border of each tag, in bit cells: 1 (AprilTag) or 2 (Kalibr);
//                         # files with Kalibr's key names default to 2, as Kalibr prints them
//
// An id matrix: the grid's geometry with any id in each cell (a board cut from
// a larger sheet), instead of rows, cols and first_id:
//   ids:                  # rows as printed, top row first; -1: a cell without a tag
//     - [17, 200, -1]
//     - [5, 93, 41]
//
// A tag list: tags anywhere, instead of rows, cols, tag_spacing and first_id:
//   tags:                 # bottom-left corner of each black square, length unit
//     - {id: 7, x: 0, y: 0}
//     - {id: 3, x: 50, y: 12}
//
// Target frame (docs/conventions.md): for a grid and an id matrix, origin at
// the outer bottom-left corner of the black square in the bottom-left cell
// (tag `first_id` of a grid), x along a row (to the right as printed), y up
// the columns, z out of the printed face; a tag list gives positions in it.
// A tag's corners come in the AprilTag library's order: bottom-left,
// bottom-right, top-right, top-left.
//
//   StatusOr<Target> target = LoadTarget("resources/targets/aprilgrid-6x6.yaml");
//   std::array<Eigen::Vector3d, 4> corners = target->TagCorners(7);
//   for (int index = 0; index < target->NumTags(); ++index) Use(target->TagId(index));
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

enum class TargetLayout {
  kGrid,      // rows × cols, ids first_id, first_id + 1, ... from the bottom-left
  kIdMatrix,  // the grid's geometry, any id in each cell, or none
  kTagList,   // each tag placed on its own
};

// One tag of a tag list: its id and the bottom-left corner of its black
// square in the target frame, length_unit.
struct TargetTag {
  int id = 0;
  double x = 0;
  double y = 0;
};

struct Target {
  std::string family = "tag36h11";
  int rows = 6;  // grid and id matrix; 0 for a tag list
  int cols = 6;
  double tag_size = 30;      // black square's edge, length_unit; 0.1 mm to 10 m (Validate)
  double tag_spacing = 0.3;  // gap between neighbouring black squares / tag_size; grid and id matrix
  int first_id = 0;          // grid only
  LengthUnit length_unit = LengthUnit::kMillimetre;
  double margin = 9;  // white sheet beyond the outer black edges, length_unit
  int border_bits = 1;  // black border cells around the data bits: 1 (AprilTag), 2 (Kalibr's aprilgrid)

  // Makes this an id-matrix board: `ids` rows as printed, top row first, all
  // of one length (asserted), -1 for a cell without a tag; rows and cols
  // become the matrix's. Tag indices run from the bottom-left along each row,
  // then upwards, skipping empty cells (a grid's order).
  void SetIdMatrix(std::vector<std::vector<int>> ids);
  // Makes this a tag-list board; tag indices follow the list. rows and cols become 0.
  void SetTagList(std::vector<TargetTag> tags);
  TargetLayout Layout() const { return layout_; }
  const std::vector<std::vector<int>>& IdMatrix() const { return id_matrix_; }  // empty unless kIdMatrix
  const std::vector<TargetTag>& TagList() const { return tag_list_; }           // empty unless kTagList

  int NumTags() const;
  int TagId(int index) const;       // index 0 .. NumTags()-1 (asserted)
  std::vector<int> TagIds() const;  // by index
  // Bit cells across a tag's black square: the family's data width + 2 × border_bits
  // (8 for tag36h11 with one border cell, 10 with two); 0 for an unknown family.
  int WidthAtBorder() const;
  double Gap() const { return tag_size * tag_spacing; }
  double Pitch() const { return tag_size + Gap(); }  // grid cell to next grid cell
  // The bounding box of all black squares: bottom-left corner ((0, 0) for a
  // grid) and extent, black edge to black edge.
  Eigen::Vector2d TagsMin() const;
  double Width() const;
  double Height() const;
  // Tag index 0 .. NumTags()-1 of `id`, if the id is on the board.
  std::optional<int> IndexOf(int id) const;
  // Corners of tag `id` (on the board, asserted) in the target frame, z = 0.
  std::array<Eigen::Vector3d, 4> TagCorners(int id) const;
  // Bottom-left corner of the black square of the tag at `index`.
  Eigen::Vector2d TagOrigin(int index) const;

  // Every rule a target file must satisfy; the message names the key.
  Status Validate() const;

 private:
  Status ValidateIdMatrix(int num_codes) const;
  Status ValidateTagList(int num_codes) const;
  Eigen::Vector2d TagsMax() const;

  TargetLayout layout_ = TargetLayout::kGrid;
  std::vector<std::vector<int>> id_matrix_;
  std::vector<TargetTag> tag_list_;
  std::vector<int> ids_;                          // by index: id matrix and tag list
  std::vector<int> cells_;                        // by index, id matrix: row from the bottom × cols + column
  std::vector<std::pair<int, int>> index_of_id_;  // (id, index), sorted: id matrix and tag list
};

// The default target: resources/targets/aprilgrid-6x6.yaml (6 × 6 tag36h11,
// 30 mm tags, 9 mm gaps), also available as the name "aprilgrid-6x6".
Target DefaultTarget();
constexpr const char* kDefaultTargetName = "aprilgrid-6x6";

// The plausible edge of a printed tag's black square (Target::Validate).
constexpr double kMinTagSizeMetres = 1e-4;
constexpr double kMaxTagSizeMetres = 10;

// Parses and validates target YAML; messages read
// "target file '<source>': <key>: <problem>".
StatusOr<Target> ParseTargetYaml(const std::string& text, const std::string& source);
// A file, or the name "aprilgrid-6x6" when no such file exists.
StatusOr<Target> LoadTarget(const std::string& path_or_name);
// hexcal's own key names, `ids:` or `tags:` for those layouts;
// ParseTargetYaml(TargetToYaml(t)) gives t back exactly.
std::string TargetToYaml(const Target& target);

// "6 x 6 tag36h11, tag 30 mm, gap 9 mm (spacing 0.3), ids 0-35";
// "34 tag36h11 tags (id matrix 6 x 6), tag 30 mm, gap 9 mm (spacing 0.3), ids 3-212";
// "5 tag36h11 tags (tag list), tag 30 mm, 250 x 120 mm, ids 5-200"
std::string DescribeTarget(const Target& target);

}  // namespace hexcal

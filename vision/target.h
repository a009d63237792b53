// The calibration target: a grid of AprilTags on a flat sheet (an "aprilgrid"
// in Kalibr's terms), read from YAML. Its tag ids make it asymmetric, so every
// detected tag says which corners of the board it shows.
//
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
// Target frame (docs/conventions.md): origin at the outer bottom-left corner of
// the black square of tag `first_id`, x along a row (to the right as printed),
// y up the columns, z out of the printed face. A tag's corners come in the
// AprilTag library's order: bottom-left, bottom-right, top-right, top-left.
//
//   StatusOr<Target> target = LoadTarget("resources/targets/aprilgrid-6x6.yaml");
//   std::array<Eigen::Vector3d, 4> corners = target->TagCorners(7);
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "core/robot.h"
#include "core/status.h"

namespace hexcal {

struct Target {
  std::string family = "tag36h11";
  int rows = 6;
  int cols = 6;
  double tag_size = 30;      // black square's edge, length_unit
  double tag_spacing = 0.3;  // gap between neighbouring black squares / tag_size
  int first_id = 0;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  double margin = 9;  // white sheet beyond the outer black edges, length_unit
  int border_bits = 1;  // black border cells around the data bits: 1 (AprilTag), 2 (Kalibr's aprilgrid)

  int NumTags() const { return rows * cols; }
  // Bit cells across a tag's black square: the family's data width + 2 × border_bits
  // (8 for tag36h11 with one border cell, 10 with two); 0 for an unknown family.
  int WidthAtBorder() const;
  double Gap() const { return tag_size * tag_spacing; }
  double Pitch() const { return tag_size + Gap(); }                      // tag origin to next tag origin
  double Width() const { return cols * tag_size + (cols - 1) * Gap(); }  // black edge to black edge
  double Height() const { return rows * tag_size + (rows - 1) * Gap(); }
  // Tag index 0 .. NumTags()-1 of `id`, if the id is on the board.
  std::optional<int> IndexOf(int id) const;
  // Corners of tag `id` (on the board, asserted) in the target frame, z = 0.
  std::array<Eigen::Vector3d, 4> TagCorners(int id) const;
  // Bottom-left corner of the black square of the tag at `index`.
  Eigen::Vector2d TagOrigin(int index) const;

  // Every rule a target file must satisfy; the message names the key.
  Status Validate() const;
};

// The default target: resources/targets/aprilgrid-6x6.yaml (6 × 6 tag36h11,
// 30 mm tags, 9 mm gaps), also available as the name "aprilgrid-6x6".
Target DefaultTarget();
constexpr const char* kDefaultTargetName = "aprilgrid-6x6";

// Parses and validates target YAML; messages read
// "target file '<source>': <key>: <problem>".
StatusOr<Target> ParseTargetYaml(const std::string& text, const std::string& source);
// A file, or the name "aprilgrid-6x6" when no such file exists.
StatusOr<Target> LoadTarget(const std::string& path_or_name);
// hexcal's own key names; ParseTargetYaml(TargetToYaml(t)) gives t back exactly.
std::string TargetToYaml(const Target& target);

// "6 x 6 tag36h11, tag 30 mm, gap 9 mm (spacing 0.3), ids 0-35"
std::string DescribeTarget(const Target& target);

}  // namespace hexcal

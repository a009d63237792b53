// AprilTag families: the names hexcal supports, their geometry, and the bit
// pattern of every tag, taken from the AprilTag library's own family tables.
//
// hexcal never uses OpenCV's ArUco dictionaries for AprilTags: OpenCV's
// DICT_APRILTAG_36h11 is rotated 180° against the AprilTag library's bitmaps
// (docs/vision.md), so printing or rendering from it would give boards whose
// tags decode with their corners in the wrong order.
//
//   std::optional<TagFamilyInfo> info = FindTagFamily("tag36h11");
//   std::vector<TagCells> cells = TagCellsOf("tag36h11", /*first_id=*/0, /*count=*/36);
//   std::vector<TagCells> board = TagCellsOf(target.family, target.TagIds(), target.border_bits);
//   bool black = cells[0].IsBlack(/*row=*/1, /*col=*/1);  // row 0 is the top as printed
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

struct apriltag_family;  // <apriltag/apriltag.h>

namespace hexcal {

struct TagFamilyInfo {
  std::string name;         // "tag36h11"
  int width_at_border = 0;  // cells across the black border: 8 for tag36h11
  int total_width = 0;      // cells including the white ring around it: 10
  int num_codes = 0;        // tags in the family: 587
  int min_hamming = 0;      // minimum Hamming distance between codes: 11
};

// Families with a black border and a white ring outside it (AprilTag's
// classic layout): tag36h11, tag25h9, tag16h5.
std::vector<std::string> SupportedTagFamilies();
std::optional<TagFamilyInfo> FindTagFamily(const std::string& name);

// The cells of one tag, `total_width` × `total_width`, row-major, row 0 at the
// top and column 0 at the left as the tag is printed upright.
struct TagCells {
  int id = 0;
  int total_width = 0;
  std::vector<uint8_t> black;  // 1 = black cell
  bool IsBlack(int row, int col) const { return black[static_cast<size_t>(row * total_width + col)] != 0; }
};

// Cells of tags first_id .. first_id + count - 1. The family must be supported
// and the ids in range (asserted). `border_bits` 2 thickens the black border
// to two cells (Kalibr's aprilgrid): total_width grows by 2, the white ring
// stays one cell.
std::vector<TagCells> TagCellsOf(const std::string& family, int first_id, int count, int border_bits = 1);
// Cells of the tags `ids`, in that order (a target's: Target::TagIds()).
std::vector<TagCells> TagCellsOf(const std::string& family, const std::vector<int>& ids, int border_bits = 1);

// Owner of an AprilTag library family object; a detector needs its own one
// (the library keeps per-detector decode tables in it).
struct AprilTagFamilyDeleter {
  void operator()(apriltag_family* family) const;
};
using AprilTagFamilyPtr = std::unique_ptr<apriltag_family, AprilTagFamilyDeleter>;
// nullptr when `name` is not a supported family.
AprilTagFamilyPtr CreateAprilTagFamily(const std::string& name);

}  // namespace hexcal

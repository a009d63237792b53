// Target geometry and validation; the YAML form is in target_yaml.cc.
#include "vision/target.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/csv.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

std::string Int(long long value) { return std::to_string(value); }

// (id, index) sorted by id, then index: duplicates sit next to each other.
std::vector<std::pair<int, int>> SortedIndex(const std::vector<int>& ids) {
  std::vector<std::pair<int, int>> index;
  for (size_t i = 0; i < ids.size(); ++i) index.emplace_back(ids[i], static_cast<int>(i));
  std::sort(index.begin(), index.end());
  return index;
}

// "row 2, column 3" of an id matrix, rows counted from the top as printed.
std::string CellName(int row_from_bottom, int col, int rows) {
  return "row " + Int(rows - row_from_bottom) + ", column " + Int(col + 1);
}

}  // namespace

void Target::SetIdMatrix(std::vector<std::vector<int>> ids) {
  layout_ = TargetLayout::kIdMatrix;
  id_matrix_ = std::move(ids);
  tag_list_.clear();
  rows = static_cast<int>(id_matrix_.size());
  cols = rows > 0 ? static_cast<int>(id_matrix_[0].size()) : 0;
  ids_.clear();
  cells_.clear();
  for (int row = 0; row < rows; ++row) {  // from the bottom: the matrix's last row
    const std::vector<int>& printed = id_matrix_[static_cast<size_t>(rows - 1 - row)];
    assert(static_cast<int>(printed.size()) == cols);
    for (int col = 0; col < cols; ++col) {
      if (printed[static_cast<size_t>(col)] == -1) continue;
      ids_.push_back(printed[static_cast<size_t>(col)]);
      cells_.push_back(row * cols + col);
    }
  }
  index_of_id_ = SortedIndex(ids_);
}

void Target::SetTagList(std::vector<TargetTag> tags) {
  layout_ = TargetLayout::kTagList;
  tag_list_ = std::move(tags);
  id_matrix_.clear();
  cells_.clear();
  rows = cols = 0;
  ids_.clear();
  for (const TargetTag& tag : tag_list_) ids_.push_back(tag.id);
  index_of_id_ = SortedIndex(ids_);
}

int Target::NumTags() const { return layout_ == TargetLayout::kGrid ? rows * cols : static_cast<int>(ids_.size()); }

int Target::TagId(int index) const {
  assert(index >= 0 && index < NumTags());
  return layout_ == TargetLayout::kGrid ? first_id + index : ids_[static_cast<size_t>(index)];
}

std::vector<int> Target::TagIds() const {
  std::vector<int> ids;
  for (int index = 0; index < NumTags(); ++index) ids.push_back(TagId(index));
  return ids;
}

std::optional<int> Target::IndexOf(int id) const {
  if (layout_ == TargetLayout::kGrid) {
    const int index = id - first_id;
    if (index < 0 || index >= NumTags()) return std::nullopt;
    return index;
  }
  const auto found = std::lower_bound(index_of_id_.begin(), index_of_id_.end(), std::make_pair(id, 0));
  if (found == index_of_id_.end() || found->first != id) return std::nullopt;
  return found->second;
}

Eigen::Vector2d Target::TagOrigin(int index) const {
  assert(index >= 0 && index < NumTags());
  switch (layout_) {
    case TargetLayout::kGrid:
      return {(index % cols) * Pitch(), (index / cols) * Pitch()};
    case TargetLayout::kIdMatrix: {
      const int cell = cells_[static_cast<size_t>(index)];
      return {(cell % cols) * Pitch(), (cell / cols) * Pitch()};
    }
    case TargetLayout::kTagList:
      break;
  }
  const TargetTag& tag = tag_list_[static_cast<size_t>(index)];
  return {tag.x, tag.y};
}

std::array<Eigen::Vector3d, 4> Target::TagCorners(int id) const {
  const std::optional<int> index = IndexOf(id);
  assert(index.has_value());
  const Eigen::Vector2d o = TagOrigin(*index);
  const double s = tag_size;
  return {Eigen::Vector3d(o.x(), o.y(), 0), Eigen::Vector3d(o.x() + s, o.y(), 0),
          Eigen::Vector3d(o.x() + s, o.y() + s, 0), Eigen::Vector3d(o.x(), o.y() + s, 0)};
}

Eigen::Vector2d Target::TagsMin() const {
  if (layout_ == TargetLayout::kGrid || NumTags() == 0) return Eigen::Vector2d::Zero();
  Eigen::Vector2d lo = TagOrigin(0);
  for (int index = 1; index < NumTags(); ++index) lo = lo.cwiseMin(TagOrigin(index));
  return lo;
}

Eigen::Vector2d Target::TagsMax() const {
  if (layout_ == TargetLayout::kGrid) {
    return {cols * tag_size + (cols - 1) * Gap(), rows * tag_size + (rows - 1) * Gap()};
  }
  if (NumTags() == 0) return Eigen::Vector2d::Zero();
  Eigen::Vector2d hi = TagOrigin(0);
  for (int index = 1; index < NumTags(); ++index) hi = hi.cwiseMax(TagOrigin(index));
  return hi + Eigen::Vector2d::Constant(tag_size);
}

double Target::Width() const { return TagsMax().x() - TagsMin().x(); }
double Target::Height() const { return TagsMax().y() - TagsMin().y(); }

Status Target::Validate() const {
  const std::optional<TagFamilyInfo> info = FindTagFamily(family);
  if (!info) {
    std::string names;
    for (const std::string& name : SupportedTagFamilies()) names += (names.empty() ? "" : ", ") + name;
    return Status::BadInput("family: '" + family + "' is not supported; expected one of " + names);
  }
  if (layout_ == TargetLayout::kGrid) {
    if (rows < 1) return Status::BadInput("rows: must be at least 1, found " + Int(rows));
    if (cols < 1) return Status::BadInput("cols: must be at least 1, found " + Int(cols));
    if (first_id < 0) return Status::BadInput("first_id: must be at least 0, found " + Int(first_id));
    const long long last = static_cast<long long>(first_id) + static_cast<long long>(rows) * cols - 1;
    if (last >= info->num_codes) {
      return Status::BadInput("first_id: ids " + Int(first_id) + " to " + Int(last) + " exceed the " +
                              Int(info->num_codes) + " tags of " + family);
    }
  } else if (layout_ == TargetLayout::kIdMatrix) {
    if (Status s = ValidateIdMatrix(info->num_codes); !s.ok()) return s;
  }
  if (!(tag_size > 0) || !std::isfinite(tag_size)) {
    return Status::BadInput("tag_size: must be a positive length, found " + FormatNumber(tag_size));
  }
  // A printable tag: 0.1 mm to 10 m. 1e300 mm printed a PDF 301 digits wide;
  // 1e-300 made every pose a rounding error (issue 36).
  const double unit = MetresPerUnit(length_unit);
  if (tag_size * unit < kMinTagSizeMetres || tag_size * unit > kMaxTagSizeMetres) {
    const std::string name = LengthUnitName(length_unit);
    return Status::BadInput("tag_size: " + FormatNumber(tag_size) + " " + name + " is outside [" +
                            FormatNumber(kMinTagSizeMetres / unit) + ", " + FormatNumber(kMaxTagSizeMetres / unit) +
                            "] " + name);
  }
  // AprilTag needs white around each black square to find it: at least one
  // bit cell between neighbours and at the edge of the sheet.
  if (border_bits != 1 && border_bits != 2) {
    return Status::BadInput("border_bits: must be 1 (AprilTag's tags) or 2 (Kalibr's aprilgrid), found " +
                            Int(border_bits));
  }
  // With a two-cell border the edge fit reaches two cells out: keep that white.
  const double cell_ratio = static_cast<double>(border_bits) / WidthAtBorder();
  const std::string cells = border_bits == 1 ? "one bit cell" : "two bit cells";
  if (layout_ == TargetLayout::kTagList) {
    if (Status s = ValidateTagList(info->num_codes); !s.ok()) return s;
  } else if (!(tag_spacing >= cell_ratio) || !std::isfinite(tag_spacing)) {
    return Status::BadInput("tag_spacing: " + FormatNumber(tag_spacing) + " leaves less than " + cells + " (tag_size/" +
                            Int(WidthAtBorder()) + " each) of white between tags; use at least " +
                            FormatNumber(cell_ratio) + " (Kalibr's default is 0.3)");
  }
  if (!(margin >= tag_size * cell_ratio) || !std::isfinite(margin)) {
    return Status::BadInput("margin: " + FormatNumber(margin) + " is less than " + cells + " (" +
                            FormatNumber(tag_size * cell_ratio) + ") of white around the outer tags");
  }
  return Status::Ok();
}

Status Target::ValidateIdMatrix(int num_codes) const {
  if (rows != static_cast<int>(id_matrix_.size())) {
    return Status::BadInput("rows: " + Int(rows) + ", but ids has " + Int(static_cast<long long>(id_matrix_.size())) +
                            " rows");
  }
  if (rows < 1 || cols < 1) return Status::BadInput("ids: expected at least one row of at least one entry");
  if (cols != static_cast<int>(id_matrix_[0].size())) {
    return Status::BadInput("cols: " + Int(cols) + ", but the rows of ids have " +
                            Int(static_cast<long long>(id_matrix_[0].size())) + " entries");
  }
  if (ids_.empty()) return Status::BadInput("ids: no tag on the board (every entry is -1)");
  for (size_t index = 0; index < ids_.size(); ++index) {
    const int id = ids_[index], cell = cells_[index];
    if (id < 0 || id >= num_codes) {
      return Status::BadInput("ids: " + CellName(cell / cols, cell % cols, rows) + ": " + Int(id) +
                              " is not a tag of " + family + " (0 to " + Int(num_codes - 1) + ", or -1 for no tag)");
    }
  }
  for (size_t k = 1; k < index_of_id_.size(); ++k) {
    if (index_of_id_[k].first != index_of_id_[k - 1].first) continue;
    int a = cells_[static_cast<size_t>(index_of_id_[k - 1].second)];
    int b = cells_[static_cast<size_t>(index_of_id_[k].second)];
    if (a / cols < b / cols) std::swap(a, b);  // as printed: the upper row first
    return Status::BadInput("ids: id " + Int(index_of_id_[k].first) + " appears twice (" +
                            CellName(a / cols, a % cols, rows) + " and " + CellName(b / cols, b % cols, rows) + ")");
  }
  return Status::Ok();
}

// Each black square needs border_bits cells of white all round (the edge fit
// reaches that far out): two squares' Chebyshev gap must be at least that.
Status Target::ValidateTagList(int num_codes) const {
  if (tag_list_.empty()) return Status::BadInput("tags: expected at least one tag");
  for (const TargetTag& tag : tag_list_) {
    if (tag.id < 0 || tag.id >= num_codes) {
      return Status::BadInput("tags: id " + Int(tag.id) + " is not a tag of " + family + " (0 to " +
                              Int(num_codes - 1) + ")");
    }
    if (!std::isfinite(tag.x) || !std::isfinite(tag.y)) {
      return Status::BadInput("tags: id " + Int(tag.id) + ": x and y must be finite");
    }
  }
  for (size_t k = 1; k < index_of_id_.size(); ++k) {
    if (index_of_id_[k].first == index_of_id_[k - 1].first) {
      return Status::BadInput("tags: id " + Int(index_of_id_[k].first) + " appears twice (entries " +
                              Int(index_of_id_[k - 1].second + 1) + " and " + Int(index_of_id_[k].second + 1) + ")");
    }
  }
  const double white = tag_size * border_bits / WidthAtBorder();
  const std::string cells = border_bits == 1 ? "one bit cell" : "two bit cells";
  for (size_t a = 0; a < tag_list_.size(); ++a) {
    for (size_t b = a + 1; b < tag_list_.size(); ++b) {
      const double gap =
          std::max(std::abs(tag_list_[a].x - tag_list_[b].x), std::abs(tag_list_[a].y - tag_list_[b].y)) - tag_size;
      if (gap >= white) continue;
      const std::string pair = "tags " + Int(tag_list_[a].id) + " and " + Int(tag_list_[b].id);
      if (gap < 0) return Status::BadInput("tags: " + pair + " overlap");
      return Status::BadInput("tags: " + pair + " are " + FormatNumber(gap) + " apart, less than " + cells + " (" +
                              FormatNumber(white) + ") of white");
    }
  }
  return Status::Ok();
}

int Target::WidthAtBorder() const {
  const std::optional<TagFamilyInfo> info = FindTagFamily(family);
  return info ? info->width_at_border - 2 + 2 * border_bits : 0;  // the library's families have one border cell
}

Target DefaultTarget() { return Target(); }

}  // namespace hexcal

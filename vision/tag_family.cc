#include "vision/tag_family.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag16h5.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>

#include <algorithm>
#include <cassert>
#include <cstdlib>

namespace hexcal {
namespace {

struct FamilyEntry {
  const char* name;
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};

constexpr FamilyEntry kFamilies[] = {
    {"tag36h11", tag36h11_create, tag36h11_destroy},
    {"tag25h9", tag25h9_create, tag25h9_destroy},
    {"tag16h5", tag16h5_create, tag16h5_destroy},
};

const FamilyEntry* FindEntry(const std::string& name) {
  for (const FamilyEntry& entry : kFamilies) {
    if (name == entry.name) return &entry;
  }
  return nullptr;
}

}  // namespace

std::vector<std::string> SupportedTagFamilies() {
  std::vector<std::string> names;
  for (const FamilyEntry& entry : kFamilies) names.emplace_back(entry.name);
  return names;
}

std::optional<TagFamilyInfo> FindTagFamily(const std::string& name) {
  AprilTagFamilyPtr family = CreateAprilTagFamily(name);
  if (!family) return std::nullopt;
  TagFamilyInfo info;
  info.name = name;
  info.width_at_border = family->width_at_border;
  info.total_width = family->total_width;
  info.num_codes = static_cast<int>(family->ncodes);
  info.min_hamming = static_cast<int>(family->h);
  return info;
}

namespace {

// The same tag with its black border `extra` cells thicker: the data grows
// apart from the white ring, the new cells black.
TagCells ThickenBorder(const TagCells& tag, int extra) {
  TagCells thick;
  thick.id = tag.id;
  thick.total_width = tag.total_width + 2 * extra;
  thick.black.assign(static_cast<size_t>(thick.total_width * thick.total_width), 0);
  const int last = thick.total_width - 1;
  for (int row = 0; row < thick.total_width; ++row) {
    for (int col = 0; col < thick.total_width; ++col) {
      const int ring = std::min(std::min(row, col), std::min(last - row, last - col));
      bool black = ring >= 1 && ring <= extra + 1;  // the border, old and new cells
      if (ring > extra + 1) black = tag.IsBlack(row - extra, col - extra);
      thick.black[static_cast<size_t>(row * thick.total_width + col)] = black ? 1 : 0;
    }
  }
  return thick;
}

}  // namespace

std::vector<TagCells> TagCellsOf(const std::string& family_name, const std::vector<int>& ids, int border_bits) {
  AprilTagFamilyPtr family = CreateAprilTagFamily(family_name);
  assert(family && border_bits >= 1);
  std::vector<TagCells> tags;
  tags.reserve(ids.size());
  for (const int id : ids) {
    assert(id >= 0 && id < static_cast<int>(family->ncodes));
    // apriltag_to_image draws the tag as the library decodes it: white = 255.
    image_u8_t* image = apriltag_to_image(family.get(), id);
    TagCells cells;
    cells.id = id;
    cells.total_width = image->width;
    cells.black.resize(static_cast<size_t>(image->width * image->height));
    for (int row = 0; row < image->height; ++row) {
      for (int col = 0; col < image->width; ++col) {
        cells.black[static_cast<size_t>(row * image->width + col)] = image->buf[row * image->stride + col] == 0;
      }
    }
    // Debian's libapriltag 3.3 does not export image_u8_destroy (nor matd_*);
    // the image and its buffer come from calloc, as that function assumes.
    free(image->buf);
    free(image);
    tags.push_back(border_bits > 1 ? ThickenBorder(cells, border_bits - 1) : std::move(cells));
  }
  return tags;
}

std::vector<TagCells> TagCellsOf(const std::string& family, int first_id, int count, int border_bits) {
  std::vector<int> ids(static_cast<size_t>(std::max(count, 0)));
  for (int k = 0; k < count; ++k) ids[static_cast<size_t>(k)] = first_id + k;
  return TagCellsOf(family, ids, border_bits);
}

void AprilTagFamilyDeleter::operator()(apriltag_family* family) const {
  if (family == nullptr) return;
  const FamilyEntry* entry = FindEntry(family->name);
  assert(entry != nullptr);
  entry->destroy(family);
}

AprilTagFamilyPtr CreateAprilTagFamily(const std::string& name) {
  const FamilyEntry* entry = FindEntry(name);
  if (entry == nullptr) return nullptr;
  return AprilTagFamilyPtr(entry->create());
}

}  // namespace hexcal

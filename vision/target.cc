#include "vision/target.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <filesystem>
#include <locale>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/yaml_document.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

// hexcal's key, and the Kalibr aprilgrid key that means the same ("" if none).
struct KeyPair {
  const char* hexcal;
  const char* kalibr;
};
constexpr KeyPair kKeys[] = {
    {"family", ""},   {"rows", "tagRows"}, {"cols", "tagCols"}, {"tag_size", "tagSize"}, {"tag_spacing", "tagSpacing"},
    {"first_id", ""}, {"length_unit", ""}, {"margin", ""},      {"target_type", ""},
    {"border_bits", ""},
};

std::string KnownKeys() {
  std::string keys;
  for (const KeyPair& key : kKeys) {
    keys += (keys.empty() ? "" : ", ") + std::string(key.hexcal);
    if (*key.kalibr) keys += " (" + std::string(key.kalibr) + ")";
  }
  return keys;
}

class TargetReader {
 public:
  explicit TargetReader(const std::string& source) : label_("target file '" + source + "'") {}

  StatusOr<Target> Read(const std::string& text) const {
    const StatusOr<YAML::Node> root = LoadYamlDocument(text, label_);
    if (!root.ok()) return root.status();
    if (!root->IsMap()) return Error("top level", "expected a mapping with keys " + KnownKeys());
    return WithYamlBackstop<Target>(label_, [&] { return ReadMap(*root); });
  }

 private:
  Status Error(const std::string& key, const std::string& problem) const {
    return Status::Error(label_ + ": " + key + ": " + problem);
  }

  StatusOr<Target> ReadMap(const YAML::Node& root) const {
    for (const auto& item : root) {
      const std::string key = item.first.Scalar();
      const bool known = std::any_of(std::begin(kKeys), std::end(kKeys), [&](const KeyPair& pair) {
        return key == pair.hexcal || (*pair.kalibr && key == pair.kalibr);
      });
      if (!known) return Error(key, "unknown key; expected " + KnownKeys());
    }
    bool kalibr_names = false;
    for (const KeyPair& pair : kKeys) {
      if (!*pair.kalibr || !root[pair.kalibr]) continue;
      if (root[pair.hexcal]) {
        return Error(pair.kalibr, std::string("given together with ") + pair.hexcal + "; use one of the two");
      }
      kalibr_names = true;
    }
    Target target;
    if (const YAML::Node type = root["target_type"]) {
      if (!type.IsScalar() || type.Scalar() != "aprilgrid") {
        return Error("target_type", "only 'aprilgrid' is supported");
      }
    }
    if (const YAML::Node family = root["family"]) {
      if (!family.IsScalar()) return Error("family", "expected a family name");
      target.family = family.Scalar();
    }
    if (Status s = ReadInt(root, "rows", "tagRows", &target.rows); !s.ok()) return s;
    if (Status s = ReadInt(root, "cols", "tagCols", &target.cols); !s.ok()) return s;
    if (Status s = ReadNumber(root, "tag_size", "tagSize", &target.tag_size); !s.ok()) return s;
    if (Status s = ReadNumber(root, "tag_spacing", "tagSpacing", &target.tag_spacing); !s.ok()) return s;
    target.first_id = 0;
    if (root["first_id"]) {
      if (Status s = ReadInt(root, "first_id", "", &target.first_id); !s.ok()) return s;
    }
    if (const YAML::Node unit = root["length_unit"]) {
      const std::optional<LengthUnit> parsed = unit.IsScalar() ? ParseLengthUnit(unit.Scalar()) : std::nullopt;
      if (!parsed) return Error("length_unit", "expected mm, cm or m");
      target.length_unit = *parsed;
    } else if (kalibr_names) {
      target.length_unit = LengthUnit::kMetre;  // Kalibr's aprilgrid files are in metres
    } else {
      return Error("length_unit", "missing (mm, cm or m)");
    }
    target.border_bits = kalibr_names ? 2 : 1;  // Kalibr prints its aprilgrid with a two-cell border
    if (root["border_bits"]) {
      if (Status s = ReadInt(root, "border_bits", "", &target.border_bits); !s.ok()) return s;
    }
    if (root["margin"]) {
      if (Status s = ReadNumber(root, "margin", "", &target.margin); !s.ok()) return s;
    } else if (target.WidthAtBorder() > 0) {
      target.margin = std::max(target.Gap(), 2.0 * target.tag_size / target.WidthAtBorder());
    }
    if (Status s = target.Validate(); !s.ok()) return Status::Error(label_ + ": " + s.message());
    return target;
  }

  // The value under the hexcal or the Kalibr name; both names are checked
  // above not to be given together.
  StatusOr<double> ReadValue(const YAML::Node& root, const char* key, const char* kalibr) const {
    const bool use_kalibr = *kalibr && root[kalibr];
    const char* name = use_kalibr ? kalibr : key;
    const YAML::Node node = root[name];
    if (!node) {
      return Error(key, std::string("missing") + (*kalibr ? std::string(" (or ") + kalibr + ")" : std::string()));
    }
    if (!node.IsScalar()) return Error(name, "expected a number");
    StatusOr<double> value = ParseNumber(node.Scalar());
    if (!value.ok()) return Error(name, Excerpt(node.Scalar()) + " is not a finite number");
    return *value;
  }

  Status ReadNumber(const YAML::Node& root, const char* key, const char* kalibr, double* out) const {
    StatusOr<double> value = ReadValue(root, key, kalibr);
    if (!value.ok()) return value.status();
    *out = *value;
    return Status::Ok();
  }

  Status ReadInt(const YAML::Node& root, const char* key, const char* kalibr, int* out) const {
    StatusOr<double> value = ReadValue(root, key, kalibr);
    if (!value.ok()) return value.status();
    if (*value != std::floor(*value) || std::abs(*value) > 1e9) {
      return Error(*kalibr && root[kalibr] ? kalibr : key, "expected a whole number, found " + FormatNumber(*value));
    }
    *out = static_cast<int>(*value);
    return Status::Ok();
  }

  std::string label_;
};

}  // namespace

std::optional<int> Target::IndexOf(int id) const {
  const int index = id - first_id;
  if (index < 0 || index >= NumTags()) return std::nullopt;
  return index;
}

Eigen::Vector2d Target::TagOrigin(int index) const {
  assert(index >= 0 && index < NumTags());
  return {(index % cols) * Pitch(), (index / cols) * Pitch()};
}

std::array<Eigen::Vector3d, 4> Target::TagCorners(int id) const {
  const std::optional<int> index = IndexOf(id);
  assert(index.has_value());
  const Eigen::Vector2d o = TagOrigin(*index);
  const double s = tag_size;
  return {Eigen::Vector3d(o.x(), o.y(), 0), Eigen::Vector3d(o.x() + s, o.y(), 0),
          Eigen::Vector3d(o.x() + s, o.y() + s, 0), Eigen::Vector3d(o.x(), o.y() + s, 0)};
}

Status Target::Validate() const {
  const std::optional<TagFamilyInfo> info = FindTagFamily(family);
  if (!info) {
    std::string names;
    for (const std::string& name : SupportedTagFamilies()) names += (names.empty() ? "" : ", ") + name;
    return Status::Error("family: '" + family + "' is not supported; expected one of " + names);
  }
  if (rows < 1) return Status::Error("rows: must be at least 1, found " + std::to_string(rows));
  if (cols < 1) return Status::Error("cols: must be at least 1, found " + std::to_string(cols));
  if (first_id < 0) return Status::Error("first_id: must be at least 0, found " + std::to_string(first_id));
  if (static_cast<long long>(first_id) + static_cast<long long>(rows) * cols > info->num_codes) {
    return Status::Error("first_id: ids " + std::to_string(first_id) + " to " +
                         std::to_string(static_cast<long long>(first_id) + static_cast<long long>(rows) * cols - 1) +
                         " exceed the " + std::to_string(info->num_codes) + " tags of " + family);
  }
  if (!(tag_size > 0) || !std::isfinite(tag_size)) {
    return Status::Error("tag_size: must be a positive length, found " + FormatNumber(tag_size));
  }
  // AprilTag needs white around each black square to find it: at least one
  // bit cell between neighbours and at the edge of the sheet.
  if (border_bits != 1 && border_bits != 2) {
    return Status::Error("border_bits: must be 1 (AprilTag's tags) or 2 (Kalibr's aprilgrid), found " +
                         std::to_string(border_bits));
  }
  // With a two-cell border the edge fit reaches two cells out: keep that white.
  const double cell_ratio = static_cast<double>(border_bits) / WidthAtBorder();
  const std::string cells = border_bits == 1 ? "one bit cell" : "two bit cells";
  if (!(tag_spacing >= cell_ratio) || !std::isfinite(tag_spacing)) {
    return Status::Error("tag_spacing: " + FormatNumber(tag_spacing) + " leaves less than " + cells +
                         " (tag_size/" + std::to_string(WidthAtBorder()) + " each) of white between tags; use at least " +
                         FormatNumber(cell_ratio) + " (Kalibr's default is 0.3)");
  }
  if (!(margin >= tag_size * cell_ratio) || !std::isfinite(margin)) {
    return Status::Error("margin: " + FormatNumber(margin) + " is less than " + cells + " (" +
                         FormatNumber(tag_size * cell_ratio) + ") of white around the outer tags");
  }
  return Status::Ok();
}

int Target::WidthAtBorder() const {
  const std::optional<TagFamilyInfo> info = FindTagFamily(family);
  return info ? info->width_at_border - 2 + 2 * border_bits : 0;  // the library's families have one border cell
}

Target DefaultTarget() { return Target(); }

StatusOr<Target> ParseTargetYaml(const std::string& text, const std::string& source) {
  return TargetReader(source).Read(text);
}

StatusOr<Target> LoadTarget(const std::string& path_or_name) {
  std::error_code error;
  if (path_or_name == kDefaultTargetName && !std::filesystem::exists(path_or_name, error)) return DefaultTarget();
  StatusOr<std::string> text = ReadFileToString(path_or_name);
  if (!text.ok()) {
    return Status::Error(text.status().message() + " (a target file, or the built-in name " +
                         std::string(kDefaultTargetName) + ")");
  }
  return ParseTargetYaml(*text, path_or_name);
}

std::string TargetToYaml(const Target& target) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << "# hexcal AprilTag grid target (docs/vision.md). Target frame: origin at the outer\n"
      << "# bottom-left corner of tag first_id, x along a row, y up, z out of the sheet.\n"
      << "target_type: aprilgrid\n"
      << "family: " << target.family << "\n"
      << "rows: " << target.rows << "\n"
      << "cols: " << target.cols << "\n"
      << "tag_size: " << FormatNumber(target.tag_size) << "      # edge of the black square\n"
      << "tag_spacing: " << FormatNumber(target.tag_spacing) << "   # gap between tags / tag_size (Kalibr)\n"
      << "first_id: " << target.first_id << "\n"
      << "length_unit: " << LengthUnitName(target.length_unit) << "\n"
      << "margin: " << FormatNumber(target.margin) << "        # white sheet beyond the outer tags\n"
      << "border_bits: " << target.border_bits << "      # black border of each tag, bit cells\n";
  return out.str();
}

std::string DescribeTarget(const Target& target) {
  const std::string unit = LengthUnitName(target.length_unit);
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(6);
  out << target.rows << " x " << target.cols << " " << target.family << ", tag " << target.tag_size << " " << unit
      << ", gap " << target.Gap() << " " << unit << " (spacing " << target.tag_spacing << "), ids " << target.first_id
      << "-" << target.first_id + target.NumTags() - 1;
  if (target.border_bits != 1) out << ", " << target.border_bits << "-cell tag border";
  return out.str();
}

}  // namespace hexcal

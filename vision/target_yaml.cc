// The target file: reading (with Kalibr's key names), writing and describing.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <locale>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/yaml_document.h"
#include "vision/target.h"

namespace hexcal {
namespace {

// hexcal's key, and the Kalibr aprilgrid key that means the same ("" if none).
struct KeyPair {
  const char* hexcal;
  const char* kalibr;
};
constexpr KeyPair kKeys[] = {
    {"family", ""},   {"rows", "tagRows"}, {"cols", "tagCols"}, {"tag_size", "tagSize"}, {"tag_spacing", "tagSpacing"},
    {"first_id", ""}, {"length_unit", ""}, {"margin", ""},      {"target_type", ""},     {"border_bits", ""},
    {"ids", ""},      {"tags", ""},
};

// Grid keys a tag list does not take: it places every tag itself.
constexpr KeyPair kNotWithTags[] = {
    {"rows", "tagRows"}, {"cols", "tagCols"}, {"tag_spacing", "tagSpacing"}, {"first_id", ""}};

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
    return Status::BadInput(label_ + ": " + key + ": " + problem);
  }

  // Unknown keys, a key under both names, keys that do not go together.
  // Sets *kalibr_names when any Kalibr name is used.
  Status CheckKeys(const YAML::Node& root, bool* kalibr_names) const {
    for (const auto& item : root) {
      const std::string key = item.first.Scalar();
      const bool known = std::any_of(std::begin(kKeys), std::end(kKeys), [&](const KeyPair& pair) {
        return key == pair.hexcal || (*pair.kalibr && key == pair.kalibr);
      });
      if (!known) return Error(YamlKeyText(item.first), "unknown key; expected " + KnownKeys());
    }
    *kalibr_names = false;
    for (const KeyPair& pair : kKeys) {
      if (!*pair.kalibr || !root[pair.kalibr]) continue;
      if (root[pair.hexcal]) {
        return Error(pair.kalibr, std::string("given together with ") + pair.hexcal + "; use one of the two");
      }
      *kalibr_names = true;
    }
    if (root["ids"] && root["first_id"]) {
      return Error("ids", "given together with first_id; an id matrix gives every tag's id");
    }
    if (root["tags"] && root["ids"]) return Error("tags", "given together with ids; use one of the two");
    for (const KeyPair& pair : kNotWithTags) {
      const char* given = root[pair.hexcal] ? pair.hexcal : (*pair.kalibr && root[pair.kalibr] ? pair.kalibr : nullptr);
      if (root["tags"] && given) {
        return Error("tags", std::string("given together with ") + given + "; a tag list places each tag itself");
      }
    }
    return Status::Ok();
  }

  StatusOr<Target> ReadMap(const YAML::Node& root) const {
    bool kalibr_names = false;
    if (Status s = CheckKeys(root, &kalibr_names); !s.ok()) return s;
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
    if (Status s = ReadLayout(root, &target); !s.ok()) return s;
    if (Status s = ReadNumber(root, "tag_size", "tagSize", &target.tag_size); !s.ok()) return s;
    if (target.Layout() != TargetLayout::kTagList) {
      if (Status s = ReadNumber(root, "tag_spacing", "tagSpacing", &target.tag_spacing); !s.ok()) return s;
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
      // The gap (Kalibr's default spacing for a tag list), at least two bit cells.
      const double gap = target.Layout() == TargetLayout::kTagList ? 0.3 * target.tag_size : target.Gap();
      target.margin = std::max(gap, 2.0 * target.tag_size / target.WidthAtBorder());
    }
    if (Status s = target.Validate(); !s.ok()) return Status::BadInput(label_ + ": " + s.message());
    return target;
  }

  // rows, cols and first_id; or ids (with rows and cols, if given, agreeing); or tags.
  Status ReadLayout(const YAML::Node& root, Target* target) const {
    if (const YAML::Node tags = root["tags"]) {
      StatusOr<std::vector<TargetTag>> list = ReadTagList(tags);
      if (!list.ok()) return list.status();
      target->SetTagList(std::move(*list));
      return Status::Ok();
    }
    if (const YAML::Node ids = root["ids"]) {
      StatusOr<std::vector<std::vector<int>>> matrix = ReadIdMatrix(ids);
      if (!matrix.ok()) return matrix.status();
      const int rows = static_cast<int>(matrix->size()), cols = static_cast<int>((*matrix)[0].size());
      for (auto [key, kalibr, size, what] :
           {std::tuple{"rows", "tagRows", rows, " rows"}, std::tuple{"cols", "tagCols", cols, " entries in a row"}}) {
        if (!root[key] && !root[kalibr]) continue;
        int given = 0;
        if (Status s = ReadInt(root, key, kalibr, &given); !s.ok()) return s;
        if (given != size) {
          return Error(root[key] ? key : kalibr,
                       std::to_string(given) + " disagrees with ids (" + std::to_string(size) + what + ")");
        }
      }
      target->SetIdMatrix(std::move(*matrix));
      return Status::Ok();
    }
    if (Status s = ReadInt(root, "rows", "tagRows", &target->rows); !s.ok()) return s;
    if (Status s = ReadInt(root, "cols", "tagCols", &target->cols); !s.ok()) return s;
    target->first_id = 0;
    if (!root["first_id"]) return Status::Ok();
    return ReadInt(root, "first_id", "", &target->first_id);
  }

  StatusOr<std::vector<std::vector<int>>> ReadIdMatrix(const YAML::Node& node) const {
    const char* expected = "expected a list of rows as printed, top row first, each a list of ids (-1: no tag)";
    if (!node.IsSequence() || node.size() == 0) return Error("ids", expected);
    std::vector<std::vector<int>> matrix;
    for (size_t row = 0; row < node.size(); ++row) {
      const YAML::Node entries = node[row];
      const std::string name = "row " + std::to_string(row + 1);
      if (!entries.IsSequence() || entries.size() == 0)
        return Error("ids", name + ": expected a list of ids (-1: no tag)");
      if (row > 0 && entries.size() != matrix[0].size()) {
        return Error("ids", name + " has " + std::to_string(entries.size()) + " entries, row 1 has " +
                                std::to_string(matrix[0].size()));
      }
      matrix.emplace_back();
      for (size_t col = 0; col < entries.size(); ++col) {
        const std::string where = name + ", column " + std::to_string(col + 1);
        StatusOr<int> id = WholeNumber(entries[col], "ids", where);
        if (!id.ok()) return id.status();
        matrix.back().push_back(*id);
      }
    }
    return matrix;
  }

  StatusOr<std::vector<TargetTag>> ReadTagList(const YAML::Node& node) const {
    const std::string expected = "expected a list of {id: <id>, x: <x>, y: <y>}";
    if (!node.IsSequence() || node.size() == 0) return Error("tags", expected);
    std::vector<TargetTag> tags;
    for (size_t entry = 0; entry < node.size(); ++entry) {
      const YAML::Node tag = node[entry];
      const std::string where = "entry " + std::to_string(entry + 1);
      if (!tag.IsMap()) return Error("tags", where + ": " + expected);
      for (const auto& item : tag) {
        const std::string key = item.first.Scalar();
        if (key != "id" && key != "x" && key != "y")
          return Error("tags", where + ": unknown key '" + YamlKeyText(item.first) + "'; " + expected);
      }
      for (const char* key : {"id", "x", "y"}) {
        if (!tag[key]) return Error("tags", where + ": " + key + " missing; " + expected);
      }
      StatusOr<int> id = WholeNumber(tag["id"], "tags", where + ": id");
      if (!id.ok()) return id.status();
      TargetTag placed{*id, 0, 0};
      for (auto [key, out] : {std::pair{"x", &placed.x}, std::pair{"y", &placed.y}}) {
        StatusOr<double> value =
            tag[key].IsScalar() ? ParseNumber(tag[key].Scalar()) : StatusOr<double>(Status::BadInput(""));
        if (!value.ok()) return Error("tags", where + ": " + key + ": expected a finite number");
        *out = *value;
      }
      tags.push_back(placed);
    }
    return tags;
  }

  StatusOr<int> WholeNumber(const YAML::Node& node, const std::string& key, const std::string& where) const {
    StatusOr<double> value = node.IsScalar() ? ParseNumber(node.Scalar()) : StatusOr<double>(Status::BadInput(""));
    if (!value.ok() || *value != std::floor(*value) || std::abs(*value) > 1e9) {
      return Error(key, where + ": expected a whole number" +
                            (node.IsScalar() ? ", found " + Excerpt(node.Scalar()) : std::string()));
    }
    return static_cast<int>(*value);
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

void WriteLayout(const Target& target, std::ostream& out) {
  switch (target.Layout()) {
    case TargetLayout::kGrid:
      out << "rows: " << target.rows << "\n"
          << "cols: " << target.cols << "\n";
      break;
    case TargetLayout::kIdMatrix:
      out << "ids:                # rows as printed, top row first; -1: no tag\n";
      for (const std::vector<int>& row : target.IdMatrix()) {
        out << "  - [";
        for (size_t col = 0; col < row.size(); ++col) out << (col ? ", " : "") << row[col];
        out << "]\n";
      }
      break;
    case TargetLayout::kTagList:
      out << "tags:               # bottom-left corner of each black square\n";
      for (const TargetTag& tag : target.TagList()) {
        out << "  - {id: " << tag.id << ", x: " << FormatNumber(tag.x) << ", y: " << FormatNumber(tag.y) << "}\n";
      }
      break;
  }
}

}  // namespace

StatusOr<Target> ParseTargetYaml(const std::string& text, const std::string& source) {
  return TargetReader(source).Read(text);
}

StatusOr<Target> LoadTarget(const std::string& path_or_name) {
  std::error_code error;
  if (path_or_name == kDefaultTargetName && !std::filesystem::exists(path_or_name, error)) return DefaultTarget();
  StatusOr<std::string> text = ReadFileToString(path_or_name);
  if (!text.ok()) {
    return text.status().WithHint(" (a target file, or the built-in name " + std::string(kDefaultTargetName) + ")");
  }
  return ParseTargetYaml(*text, path_or_name);
}

std::string TargetToYaml(const Target& target) {
  const bool grid = target.Layout() == TargetLayout::kGrid;
  std::ostringstream out;
  out.imbue(std::locale::classic());
  if (target.Layout() == TargetLayout::kTagList) {
    out << "# hexcal AprilTag target, a tag list (docs/vision.md). Target frame: x, y as placed\n"
        << "# below, z out of the sheet.\n";
  } else {
    out << "# hexcal AprilTag grid target (docs/vision.md). Target frame: origin at the outer\n"
        << "# bottom-left corner of the bottom-left cell's tag, x along a row, y up, z out of the sheet.\n";
  }
  out << "target_type: aprilgrid\n"
      << "family: " << target.family << "\n";
  if (grid) WriteLayout(target, out);
  out << "tag_size: " << FormatNumber(target.tag_size) << "      # edge of the black square\n";
  if (target.Layout() != TargetLayout::kTagList) {
    out << "tag_spacing: " << FormatNumber(target.tag_spacing) << "   # gap between tags / tag_size (Kalibr)\n";
  }
  if (grid) out << "first_id: " << target.first_id << "\n";
  out << "length_unit: " << LengthUnitName(target.length_unit) << "\n"
      << "margin: " << FormatNumber(target.margin) << "        # white sheet beyond the outer tags\n"
      << "border_bits: " << target.border_bits << "      # black border of each tag, bit cells\n";
  if (!grid) WriteLayout(target, out);
  return out.str();
}

std::string DescribeTarget(const Target& target) {
  const std::string unit = LengthUnitName(target.length_unit);
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(6);
  const std::vector<int> ids = target.TagIds();
  const auto [lowest, highest] = std::minmax_element(ids.begin(), ids.end());
  switch (target.Layout()) {
    case TargetLayout::kGrid:
      out << target.rows << " x " << target.cols << " " << target.family;
      break;
    case TargetLayout::kIdMatrix:
      out << ids.size() << " " << target.family << " tags (id matrix " << target.rows << " x " << target.cols << ")";
      break;
    case TargetLayout::kTagList:
      out << ids.size() << " " << target.family << " tags (tag list)";
      break;
  }
  out << ", tag " << target.tag_size << " " << unit;
  if (target.Layout() == TargetLayout::kTagList) {
    out << ", " << target.Width() << " x " << target.Height() << " " << unit;
  } else {
    out << ", gap " << target.Gap() << " " << unit << " (spacing " << target.tag_spacing << ")";
  }
  if (!ids.empty()) out << ", ids " << *lowest << "-" << *highest;
  if (target.border_bits != 1) out << ", " << target.border_bits << "-cell tag border";
  return out.str();
}

}  // namespace hexcal

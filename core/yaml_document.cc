#include "core/yaml_document.h"

#include <map>

#include "core/csv.h"

namespace hexcal {

namespace {

// Nodes a duplicate-key walk visits at most: a 4 MiB file has fewer, but an
// alias may be visited once per reference (a "billion laughs" document).
constexpr int kMaxNodesChecked = 1000000;

// The first mapping under `node` that names a key twice: yaml-cpp keeps both
// entries and a lookup finds the first, so `fx: 500` then `fx: 1e300` read as
// 500 without a word (issue 36). `path` is the robot reader's form
// ("legs[2].stroke"); scalar keys only, no hexcal format has others.
Status CheckUniqueKeys(const YAML::Node& node, const std::string& label, const std::string& path, int* budget) {
  if (--*budget < 0) return Status::Ok();
  if (node.IsSequence()) {
    size_t index = 0;
    for (const YAML::Node& item : node) {
      const std::string item_path = path + "[" + std::to_string(index++) + "]";
      if (Status s = CheckUniqueKeys(item, label, item_path, budget); !s.ok()) return s;
    }
  }
  if (!node.IsMap()) return Status::Ok();
  std::map<std::string, int> lines;  // key -> the line it is first on
  for (const auto& entry : node) {
    const std::string key = YamlKeyText(entry.first);
    const std::string key_path = path.empty() ? key : path + "." + key;
    if (entry.first.IsScalar()) {
      const int line = entry.first.Mark().line + 1;
      const auto [first, inserted] = lines.emplace(entry.first.Scalar(), line);
      if (!inserted)
        return Status::BadInput(label + ": " + key_path + ": duplicate key (lines " + std::to_string(first->second) +
                                " and " + std::to_string(line) + ")");
    }
    if (Status s = CheckUniqueKeys(entry.second, label, key_path, budget); !s.ok()) return s;
  }
  return Status::Ok();
}

}  // namespace

std::string YamlKeyText(const YAML::Node& key) {
  if (key.IsScalar() && IsPlainName(key.Scalar())) return key.Scalar();
  return "the key on line " + std::to_string(key.Mark().line + 1);
}

StatusOr<YAML::Node> LoadYamlDocument(const std::string& text, const std::string& label) {
  try {
    YAML::Node root = YAML::Load(text);
    int budget = kMaxNodesChecked;
    if (Status s = CheckUniqueKeys(root, label, "", &budget); !s.ok()) return s;
    return root;
  } catch (const YAML::ParserException& e) {
    return Status::BadInput(label + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                            std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const YAML::Exception& e) {  // not a syntax error, e.g. nesting too deep
    return Status::BadInput(label + ": cannot read as YAML: " + e.what());
  }
}

StatusOr<std::vector<std::pair<std::string, std::string>>> ScalarEntries(const YAML::Node& map,
                                                                         const std::string& where) {
  if (!map.IsMap()) return Status::BadInput(where + ": expected a mapping of keys to values");
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& item : map) {
    if (!item.first.IsScalar()) return Status::BadInput(where + ": a key that is not a name");
    const std::string key = item.first.Scalar();
    if (!item.second.IsScalar())
      return Status::BadInput(where + "." + YamlKeyText(item.first) + ": expected a single value");
    entries.emplace_back(key, item.second.Scalar());
  }
  return entries;
}

}  // namespace hexcal

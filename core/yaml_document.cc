#include "core/yaml_document.h"

namespace hexcal {

StatusOr<YAML::Node> LoadYamlDocument(const std::string& text, const std::string& label) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    return Status::Error(label + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                         std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const YAML::Exception& e) {  // not a syntax error, e.g. nesting too deep
    return Status::Error(label + ": cannot read as YAML: " + e.what());
  }
}

StatusOr<std::vector<std::pair<std::string, std::string>>> ScalarEntries(const YAML::Node& map,
                                                                         const std::string& where) {
  if (!map.IsMap()) return Status::Error(where + ": expected a mapping of keys to values");
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& item : map) {
    if (!item.first.IsScalar()) return Status::Error(where + ": a key that is not a name");
    const std::string key = item.first.Scalar();
    if (!item.second.IsScalar()) return Status::Error(where + "." + key.substr(0, 40) + ": expected a single value");
    entries.emplace_back(key, item.second.Scalar());
  }
  return entries;
}

}  // namespace hexcal

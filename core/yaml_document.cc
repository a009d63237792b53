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

}  // namespace hexcal

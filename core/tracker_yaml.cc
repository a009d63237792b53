#include "core/tracker_yaml.h"

#include <cmath>

#include "core/yaml_document.h"

namespace hexcal {
namespace {

StatusOr<Eigen::Vector3d> ReadVector3(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence() || node.size() != 3) return Status::BadInput(where + ": expected [x, y, z]");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    const std::string refused = where + ": entry " + std::to_string(k + 1) + " is not a finite number";
    if (!node[k].IsScalar()) return Status::BadInput(refused);
    StatusOr<double> value = ParseNumber(node[k].Scalar());
    if (!value.ok() || !std::isfinite(*value)) return Status::BadInput(refused);
    v[k] = *value;
  }
  return v;
}

YAML::Node Vector3Node(const Eigen::Vector3d& v) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (int k = 0; k < 3; ++k) node.push_back(FormatNumber(v[k]));
  return node;
}

}  // namespace

StatusOr<TrackerSettings> ReadTrackerSection(const YAML::Node& section, const std::string& source) {
  const std::string where = source + ": tracker";
  if (!section.IsMap()) return Status::BadInput(where + ": expected a mapping (position, sigma_law, ...)");
  TrackerSettings settings;
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& item : section) {
    if (!item.first.IsScalar()) return Status::BadInput(where + ": a key that is not a name");
    const std::string key = item.first.Scalar();
    if (key == "position" || key == "reflector_normal") {
      StatusOr<Eigen::Vector3d> v = ReadVector3(item.second, where + "." + key);
      if (!v.ok()) return v.status();
      if (key == "position") {
        settings.position = *v;
      } else {
        settings.reflector_normal = *v;
      }
    } else if (!item.second.IsScalar()) {
      return Status::BadInput(where + "." + YamlKeyText(item.first) + ": expected a single value");
    } else {
      entries.emplace_back(key, item.second.Scalar());
    }
  }
  if (Status s = ApplyOptionEntries(TrackerSettingsOptions(), entries, &settings, where); !s.ok()) return s;
  std::string error;
  if (!settings.IsValid(&error)) return Status::BadInput(source + ": " + error);
  return settings;
}

YAML::Node TrackerSectionNode(const TrackerSettings& settings) {
  YAML::Node node;
  if (settings.position) node["position"] = Vector3Node(*settings.position);
  for (const OptionSpec<TrackerSettings>& spec : TrackerSettingsOptions()) node[spec.key] = OptionText(spec, settings);
  node["reflector_normal"] = Vector3Node(settings.reflector_normal);
  return node;
}

}  // namespace hexcal

#include "core/noise_yaml.h"

#include "core/yaml_document.h"

namespace hexcal {

StatusOr<NoiseModel> ReadNoiseSection(const YAML::Node& section, const std::string& where) {
  if (!section.IsMap()) return Status::BadInput(where + ": expected a mapping {position, angle_deg, leg}");
  StatusOr<std::vector<std::pair<std::string, std::string>>> entries = ScalarEntries(section, where);
  if (!entries.ok()) return entries.status();
  NoiseModel noise;
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *entries, &noise, where); !s.ok()) return s;
  return noise;
}

}  // namespace hexcal

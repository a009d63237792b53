// Robot presets compiled into the binary from resources/robots/*.yaml.
#pragma once

#include <map>
#include <string>

namespace hexcal {

// Preset name (file name without .yaml) -> YAML text.
const std::map<std::string, std::string>& EmbeddedPresets();

}  // namespace hexcal

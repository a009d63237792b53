// The one reader of a YAML `noise:` section ({position, angle_deg, leg}), for
// session.yaml and plan settings alike: keys and ranges from
// NoiseModelOptions(), unknown keys refused. Core-internal (yaml-cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "core/noise_model.h"
#include "core/status.h"

namespace hexcal {

// Keys missing from the section keep their defaults; `where` starts every
// message ("session.yaml: noise").
StatusOr<NoiseModel> ReadNoiseSection(const YAML::Node& section, const std::string& where);

}  // namespace hexcal

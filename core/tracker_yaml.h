// The one reader and writer of session.yaml's `tracker:` section
// (docs/session.md, "Planning with a laser tracker"): position and
// reflector_normal as [x, y, z], the scalar keys of TrackerSettingsOptions(),
// unknown keys refused. Core-internal (yaml-cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "core/status.h"
#include "core/tracker_model.h"

namespace hexcal {

// Keys missing from the section keep their defaults; `source` (the file)
// starts every message, then the key: "run1/session.yaml: tracker.sigma0: ...".
StatusOr<TrackerSettings> ReadTrackerSection(const YAML::Node& section, const std::string& source);
// The section as SessionConfig writes it: every key, numbers in their shortest exact form.
YAML::Node TrackerSectionNode(const TrackerSettings& settings);

}  // namespace hexcal

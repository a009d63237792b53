// libFuzzer target: the plan settings YAML (`hexcal plan --settings`,
// core/planning_model.h) against the INRIA preset. docs/hardening.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/planning_model.h"
#include "core/robot_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const hexcal::Robot robot = *hexcal::LoadRobot("inria-left-hand");
  const std::string text(reinterpret_cast<const char*>(data), size);
  const hexcal::StatusOr<hexcal::PlanSettings> settings = hexcal::ParsePlanSettings(text, "fuzz.yaml", robot);
  if (!settings.ok()) return 0;
  if (settings->measurement) {
    const hexcal::MeasurementConstraints& c = *settings->measurement;
    if (!(c.half_fov_x_deg > 0) || !(c.half_fov_y_deg > 0) || !c.base_from_camera.position.allFinite()) std::abort();
  }
  return 0;
}

#include "core/robot.h"

#include <algorithm>

namespace hexcal {

std::optional<LengthUnit> ParseLengthUnit(const std::string& text) {
  if (text == "mm") return LengthUnit::kMillimetre;
  if (text == "cm") return LengthUnit::kCentimetre;
  if (text == "m") return LengthUnit::kMetre;
  return std::nullopt;
}

const char* LengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return "mm";
    case LengthUnit::kCentimetre:
      return "cm";
    case LengthUnit::kMetre:
      return "m";
  }
  return "?";
}

double MetresPerUnit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return 1e-3;
    case LengthUnit::kCentimetre:
      return 1e-2;
    case LengthUnit::kMetre:
      return 1.0;
  }
  return 1.0;
}

std::optional<PoseBox> RobotLimits::SamplingBox() const {
  if (!sampling_box) return pose_box;
  PoseBox box = *sampling_box;
  if (!pose_box) return box;
  for (int k = 0; k < 6; ++k) {
    const auto& own = pose_box->bounds[k];
    auto& bound = box.bounds[k];
    if (own && bound) bound = Range{std::max(own->min, bound->min), std::min(own->max, bound->max)};
    else if (own) bound = own;
  }
  return box;
}

LegParameters LegParametersOf(const Leg& leg) {
  LegParameters p;
  p << leg.a_in_base, leg.b_in_platform, leg.offset;
  return p;
}

ParameterVector ParametersOf(const Robot& robot) {
  ParameterVector p;
  for (int i = 0; i < kNumLegs; ++i) {
    p.segment<kParamsPerLeg>(kParamsPerLeg * i) = LegParametersOf(robot.legs[i]);
  }
  return p;
}

Robot WithParameters(const Robot& robot, const ParameterVector& params) {
  Robot out = robot;
  for (int i = 0; i < kNumLegs; ++i) {
    const auto p = params.segment<kParamsPerLeg>(kParamsPerLeg * i);
    out.legs[i].a_in_base = p.head<3>();
    out.legs[i].b_in_platform = p.segment<3>(3);
    out.legs[i].offset = p[6];
  }
  return out;
}

Vector6d WorkspaceCentre(const Robot& robot) {
  Vector6d centre = Vector6d::Zero();
  if (const std::optional<PoseBox> box = robot.limits.SamplingBox(); box && box->IsComplete())
    for (int k = 0; k < 6; ++k) centre[k] = box->bounds[k]->Centre();
  return centre;
}

}  // namespace hexcal

#include "session/json_forms.h"

namespace hexcal::workflow {

nlohmann::json PoseJson(const Robot& robot, const Pose& pose) {
  const Vector6d v = robot.VectorFromPose(pose);
  return {{"x", v[0]}, {"y", v[1]}, {"z", v[2]}, {"q1", v[3]}, {"q2", v[4]}, {"q3", v[5]}};
}

nlohmann::json IndicesJson(const ObservabilityIndices& o) {
  return {{"O1", o.o1},
          {"O2", o.o2},
          {"O3", o.o3},
          {"O4", o.o4},
          {"sigma_min", o.sigma_min},
          {"sigma_max", o.sigma_max},
          {"poses", o.num_poses}};
}

nlohmann::json RobotJson(const Robot& robot) {
  nlohmann::json legs = nlohmann::json::array();
  for (const Leg& leg : robot.legs) {
    legs.push_back({{"a", {leg.a_in_base.x(), leg.a_in_base.y(), leg.a_in_base.z()}},
                    {"b", {leg.b_in_platform.x(), leg.b_in_platform.y(), leg.b_in_platform.z()}},
                    {"l", leg.offset},
                    {"stroke", {leg.stroke_min, leg.stroke_max}}});
  }
  return {{"name", robot.name},
          {"length_unit", LengthUnitName(robot.length_unit)},
          {"euler", EulerConventionName(robot.euler)},
          {"legs", legs}};
}

Robot RobotFromJson(JsonFields fields) {
  Robot robot;
  robot.name = fields.String("name");
  const std::optional<LengthUnit> unit = ParseLengthUnit(fields.String("length_unit"));
  const std::optional<EulerConvention> euler = ParseEulerConvention(fields.String("euler"));
  if (unit) robot.length_unit = *unit;
  if (euler) robot.euler = *euler;
  if (!unit) fields.Fail("length_unit", "not mm, cm or m");
  if (!euler) fields.Fail("euler", "not a known Euler convention");
  std::vector<JsonFields> legs = fields.Array("legs");
  if (legs.size() != robot.legs.size()) fields.Fail("legs", "expected 6 legs");
  for (size_t i = 0; i < legs.size() && i < robot.legs.size(); ++i) {
    const std::vector<double> a = legs[i].Numbers("a", 3), b = legs[i].Numbers("b", 3);
    const std::vector<double> stroke = legs[i].Numbers("stroke", 2);
    Leg& leg = robot.legs[i];
    leg.a_in_base = {a[0], a[1], a[2]};
    leg.b_in_platform = {b[0], b[1], b[2]};
    leg.offset = legs[i].Number("l");
    leg.stroke_min = stroke[0];
    leg.stroke_max = stroke[1];
  }
  return robot;
}

}  // namespace hexcal::workflow

#include "core/reading_units.h"

#include <cmath>

#include "core/csv.h"

namespace hexcal {
namespace {

bool WithinStroke(const Leg& leg, double reading, double slack_strokes) {
  const double slack = slack_strokes * (leg.stroke_max - leg.stroke_min);
  return reading >= leg.stroke_min - slack && reading <= leg.stroke_max + slack;
}

// Every reading divided by `factor` lies within its stroke.
bool AllWithinStrokes(const Robot& robot, const std::vector<LegReadings>& rows, double factor) {
  for (const LegReadings& row : rows) {
    for (int i = 0; i < kNumLegs; ++i) {
      if (!WithinStroke(robot.legs[i], row[i] / factor, 0.25)) return false;
    }
  }
  return true;
}

// Whether at least half of the readings are far outside their strokes; the
// first of them (row and leg).
bool MostlyFarOutside(const Robot& robot, const std::vector<LegReadings>& rows, size_t* row, int* leg) {
  size_t far = 0;
  for (size_t j = 0; j < rows.size(); ++j) {
    for (int i = 0; i < kNumLegs; ++i) {
      if (WithinStroke(robot.legs[i], rows[j][i], kFarOutsideStrokes)) continue;
      if (far++ == 0) {
        *row = j;
        *leg = i;
      }
    }
  }
  return far > 0 && 2 * far >= rows.size() * kNumLegs;
}

}  // namespace

Status CheckReadingsUnit(const Robot& robot, const std::vector<LegReadings>& rows, const std::string& row_label) {
  size_t row = 0;
  int leg = 0;
  if (!MostlyFarOutside(robot, rows, &row, &leg)) return Status::Ok();
  for (LengthUnit unit : {LengthUnit::kMillimetre, LengthUnit::kCentimetre, LengthUnit::kMetre}) {
    if (unit == robot.length_unit) continue;
    // A length of x robot units is x * factor readings units.
    const double factor = MetresPerUnit(robot.length_unit) / MetresPerUnit(unit);
    if (!AllWithinStrokes(robot, rows, factor)) continue;
    const Leg& at_fault = robot.legs[leg];
    const char* robot_unit = LengthUnitName(robot.length_unit);
    const std::string where = row_label.empty() ? "" : row_label + " " + std::to_string(row + 1) + ": ";
    return Status::BadInput("readings look like " + std::string(LengthUnitName(unit)) + ", the robot '" + robot.name +
                            "' is in " + robot_unit + ": " + where + "L" + std::to_string(leg + 1) + " = " +
                            FormatNumber(rows[row][leg]) + " is far outside the stroke [" +
                            FormatNumber(at_fault.stroke_min) + ", " + FormatNumber(at_fault.stroke_max) + "] " +
                            robot_unit + ", and every reading fits the strokes once converted from " +
                            LengthUnitName(unit) + " to " + robot_unit);
  }
  return Status::Ok();
}

}  // namespace hexcal

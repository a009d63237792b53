// One number format per quantity, with its unit, for every panel (issue 15):
// an error or an RMS has three significant digits ("0.00413 cm", "0.0121°",
// "0.214 px"); a pose coordinate or a reading has the robot unit's
// micrometre-level resolution ("52.249612 cm" would be six decimals: four are
// kept, as the planner's plan.csv); a ratio is "2.3×".
//
//   FormatLength(0.0041321, "cm");  // "0.00413 cm"
//   FormatRatio(2.31);              // "2.3×"
#pragma once

#include <QString>
#include <optional>

namespace hexcal::ui {

QString FormatLength(double value, const QString& unit);       // "0.00413 cm"
QString FormatAngle(double degrees);                             // "0.0121°"
QString FormatPixels(double pixels);                             // "0.214 px"
QString FormatCoordinate(double value);                          // "52.2496" (unit in the header)
QString FormatRatio(double ratio);                               // "2.3×"
// "—" for a missing figure (FK did not converge, no σ).
QString FormatLength(const std::optional<double>& value, const QString& unit);

}  // namespace hexcal::ui

// One number format per quantity, with its unit, for every panel (issues 15
// and 35): an error, a σ or an RMS has three significant digits ("0.00413
// cm", "0.0121°", "0.214 px"); a pose coordinate, a reading or a robot
// dimension has the robot unit's micrometre-level resolution ("52.249612 cm"
// would be six decimals: four are kept, as the planner's plan.csv); a
// camera's focal length or principal point one decimal of a pixel ("903.5
// px"); a ratio is "2.3×"; a count names its noun in the right number ("1
// pose", "3 poses"). In a table whose header names the unit, the cells are
// the same numbers without it (FormatSignificant, FormatCoordinate).
//
//   FormatLength(0.0041321, "cm");  // "0.00413 cm"
//   FormatCount(1, "pose");          // "1 pose"
//   FormatRatio(2.31);              // "2.3×"
#pragma once

#include <QString>
#include <optional>

namespace hexcal::ui {

QString FormatLength(double value, const QString& unit);  // "0.00413 cm"
QString FormatAngle(double degrees);                      // "0.0121°"
QString FormatPixels(double pixels);                      // "0.214 px"
QString FormatCoordinate(double value);                   // "52.2496" (unit in the header)
QString FormatRatio(double ratio);                        // "2.3×"
// "—" for a missing figure (FK did not converge, no σ).
QString FormatLength(const std::optional<double>& value, const QString& unit);
// Three significant digits, the unit in the header: "0.00413", "—" when not finite.
QString FormatSignificant(double value);
QString FormatPixelCoordinate(double pixels);               // "903.5 px": focal lengths, principal points
QString FormatSeconds(double seconds);                      // "0.82 s", "12.3 s", "95 s"
QString FormatPercent(double percent);                      // "97.5 %"
QString FormatCount(long long count, const QString& noun);  // "1 pose", "3 poses"

}  // namespace hexcal::ui

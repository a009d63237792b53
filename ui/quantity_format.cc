#include "ui/quantity_format.h"

#include <cmath>

namespace hexcal::ui {
namespace {

constexpr int kSignificant = 3;

QString Significant(double value) {
  if (!std::isfinite(value)) return "—";
  return QString::number(value, 'g', kSignificant);
}

}  // namespace

QString FormatLength(double value, const QString& unit) { return Significant(value) + " " + unit; }

QString FormatLength(const std::optional<double>& value, const QString& unit) {
  return value ? FormatLength(*value, unit) : QString("—");
}

QString FormatAngle(double degrees) { return Significant(degrees) + "°"; }

QString FormatPixels(double pixels) { return Significant(pixels) + " px"; }

QString FormatCoordinate(double value) {
  if (!std::isfinite(value)) return "—";
  // Round-off of IK (1e-15) reads as 0, not -0.0000.
  const double rounded = std::round(value * 1e4) / 1e4;
  return QString::number(rounded == 0 ? 0.0 : rounded, 'f', 4);
}

QString FormatRatio(double ratio) { return std::isfinite(ratio) ? QString::number(ratio, 'f', 1) + "×" : "—"; }

QString FormatSignificant(double value) { return Significant(value); }

QString FormatPixelCoordinate(double pixels) {
  return std::isfinite(pixels) ? QString::number(pixels, 'f', 1) + " px" : "—";
}

QString FormatSeconds(double seconds) {
  if (!std::isfinite(seconds)) return "—";
  // Whole seconds from 100 s on: 'g' would write 1.23e+03.
  return (seconds >= 100 ? QString::number(std::round(seconds), 'f', 0) : QString::number(seconds, 'g', kSignificant)) +
         " s";
}

QString FormatPercent(double percent) { return std::isfinite(percent) ? QString::number(percent, 'f', 1) + " %" : "—"; }

QString FormatCount(long long count, const QString& noun) {
  return QString::number(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace hexcal::ui

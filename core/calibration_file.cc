#include "core/calibration_file.h"

#include <yaml-cpp/yaml.h>

#include <ctime>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/robot_io.h"

namespace hexcal {
namespace {

// Text values are always double-quoted: a path or a solver message must not read as a number or a key.
std::string Quoted(const std::string& text) {
  YAML::Emitter emitter;
  emitter << YAML::DoubleQuoted << text;
  return emitter.c_str();
}

std::string Number(double v) { return FormatNumber(v); }

std::string Triple(const LegParameters& p, int first) {
  return "[" + Number(p[first]) + ", " + Number(p[first + 1]) + ", " + Number(p[first + 2]) + "]";
}

std::string LegEntry(const LegCalibration& leg) {
  std::ostringstream out;
  out << "{";
  if (leg.has_uncertainty) {
    out << "sigma_a: " << Triple(leg.std_dev, 0) << ", sigma_b: " << Triple(leg.std_dev, 3)
        << ", sigma_l: " << Number(leg.std_dev[6]) << ", variance_factor: " << Number(leg.variance_factor);
  } else {
    out << "sigma_a: null, sigma_b: null, sigma_l: null";
  }
  out << ", residual_rms: " << Number(leg.residual_rms) << ", iterations: " << leg.iterations
      << ", termination: " << Quoted(leg.termination) << ", unidentifiable_directions: " << leg.unidentifiable.size();
  std::string excluded;
  for (const RowOutlier& o : leg.outliers)
    if (o.excluded) excluded += (excluded.empty() ? "" : ", ") + std::to_string(o.measurement + 1);
  if (!excluded.empty()) out << ", excluded_measurements: [" << excluded << "]";
  out << "}";
  return out.str();
}

}  // namespace

std::string CurrentUtcTimestamp(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, format, &utc);
  return text;
}

std::string CalibratedRobotToYaml(const CalibrationResult& result, const CalibrationInputs& inputs) {
  const CalibrationOptions& options = inputs.options;
  std::ostringstream out;
  out << RobotToYaml(result.robot);
  out << "# What produced these parameters and how well they are known: docs/calibration.md\n"
      << "calibration:\n"
      << "  method: \"implicit least squares per leg (paper eq. 4), Ceres Levenberg-Marquardt\"\n"
      << "  date: " << Quoted(inputs.date) << "\n"
      << "  nominal_robot: " << Quoted(inputs.nominal_robot) << "\n"
      << "  measurements: {path: " << Quoted(inputs.measurements_path) << ", count: " << result.num_measurements
      << "}\n"
      << "  options: {loss: " << RobustLossName(options.loss) << ", loss_scale: " << Number(options.loss_scale)
      << ", weighted: " << (options.weighted ? "true" : "false") << ", noise: {" << NoiseModelText(options.noise)
      << "}, max_iterations: " << options.max_iterations;
  if (options.outliers.enabled) {
    out << ", outliers: {threshold: " << Number(options.outliers.threshold)
        << ", keep: " << (options.outliers.keep ? "true" : "false") << "}";
  }
  out << "}\n"
      << "  # sigma: one standard deviation (length unit), covariance scaled by variance_factor = SSR/(N-7)\n"
      << "  # residual_rms: RMS of |P + R b - a| - (L + l) over the measurements fitted (length unit)\n"
      << "  # excluded_measurements: rows left out of that leg as outliers (docs/calibration.md)\n"
      << "  length_unit: " << LengthUnitName(result.robot.length_unit) << "\n"
      << "  legs:\n";
  for (const LegCalibration& leg : result.legs) out << "    - " << LegEntry(leg) << "\n";
  return out.str();
}

Status SaveCalibratedRobot(const std::string& path, const CalibrationResult& result, const CalibrationInputs& inputs) {
  return WriteFileAtomically(path, CalibratedRobotToYaml(result, inputs));
}

}  // namespace hexcal

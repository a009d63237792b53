// Calibration measurements: per row the measured platform pose in the base
// frame and the six leg sensor readings taken at it.
//
// File (docs/conventions.md, "Files"): a CSV with the columns
//   x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6
// in any order; other columns are ignored (so `hexcal ik --out` output reads
// as measurements). Lengths in the robot's unit, angles in degrees. Every
// error names the file, the line and the column:
//   m.csv: missing column 'L4' (header: x,y,z,q1,q2,q3,L1,L2,L3)
//   m.csv:12: column 'q2': 'nan' is not a finite number
//
//   StatusOr<std::vector<Measurement>> rows = LoadMeasurements("measurements.csv");
//   if (!rows.ok()) return rows.status();
//   Status saved = SaveMeasurements("copy.csv", *rows);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/status.h"

namespace hexcal {

struct Measurement {
  Vector6d pose = Vector6d::Zero();        // [x, y, z, q1, q2, q3]: robot unit, degrees
  LegReadings legs = LegReadings::Zero();  // L1..L6, robot unit
  // Covariance of `pose` when the sensor gives one per pose (a camera:
  // registration.h), robot unit² and degrees²; it replaces the noise model's
  // pose terms in the weights (noise_model.h). Not stored in the CSV.
  std::optional<Matrix6d> pose_covariance;
};

// The column names, in the order SaveMeasurements writes them.
const std::vector<std::string>& MeasurementColumns();

// Reads a measurements CSV; at least one data row.
StatusOr<std::vector<Measurement>> LoadMeasurements(const std::string& path);
// The same, from text in memory; `source` names it in messages.
StatusOr<std::vector<Measurement>> ParseMeasurements(const std::string& text, const std::string& source);

// Writes x,y,z,q1,q2,q3,L1..L6 atomically, numbers in their shortest exact form.
Status SaveMeasurements(const std::string& path, const std::vector<Measurement>& measurements);

}  // namespace hexcal

// Validation by forward kinematics (paper section 8, Tables 4 and 5): for each
// measurement, the pose the robot model predicts from the leg readings — local
// FK started at the measured pose, so it tracks the assembly mode the robot is
// in — against the measured pose. Run it with the nominal and the calibrated
// robot on poses not used for the calibration to see the gain.
//
//   StatusOr<ValidationReport> report = Validate(robot, measurements);
//   if (report.ok()) std::cout << report->position.rms << " " << report->orientation_deg.max;
#pragma once

#include <string>
#include <vector>

#include "core/error_stats.h"
#include "core/measurements.h"
#include "core/status.h"

namespace hexcal {

struct ValidationRow {
  bool ok = false;                   // forward kinematics converged
  double position_error = 0;         // |P_fk - P_measured|, robot unit
  double orientation_error_deg = 0;  // rotation angle between R_fk and R_measured, degrees
  std::string error;                 // why FK failed, when !ok
};

struct ValidationReport {
  std::vector<ValidationRow> rows;  // one per measurement, in file order
  int failed = 0;                   // rows where FK did not converge (not in the statistics)
  ErrorStats position;              // over the converged rows, robot unit
  ErrorStats orientation_deg;       // over the converged rows, degrees
};

// Fails for no measurements, non-finite input, or when FK converges for none of the rows.
StatusOr<ValidationReport> Validate(const Robot& robot, const std::vector<Measurement>& measurements);

}  // namespace hexcal

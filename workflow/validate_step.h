// The Validate step on a file (`hexcal validate`): forward kinematics from
// each row's leg readings against its measured pose (core/validation.h).
//
//   StatusOr<ValidateResult> result = ValidateMeasurements({"calibrated.yaml", "held_out.csv"});
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/noise_model.h"
#include "core/status.h"
#include "core/validation.h"
#include "report/calibration_verdict.h"
#include "report/expected_error.h"

namespace hexcal::workflow {

struct ValidateRequest {
  std::string robot;         // robot file or preset name
  std::string measurements;  // measurements CSV: x,y,z,q1,q2,q3,L1..L6
  NoiseModel noise;          // of the measurements (--noise-*): what the verdict compares with
};

struct ValidateResult {
  std::string robot, length_unit, measurements;
  ValidationReport report;
  ExpectedPoseError expected;  // what `noise` predicts at the measured poses (expected_error.h)
  Verdict verdict;             // the errors against `expected` (calibration_verdict.h)
};

StatusOr<ValidateResult> ValidateMeasurements(const ValidateRequest& request);

// The keys of the report, then "verdict" (Verdict::ToJson).
nlohmann::json ToJson(const ValidateResult& result);
// The table of errors, then the verdict's lines.
std::string FormatValidateSummary(const ValidateResult& result);

}  // namespace hexcal::workflow

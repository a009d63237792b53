// The Validate step on a file (`hexcal validate`): forward kinematics from
// each row's leg readings against its measured pose (core/validation.h).
//
//   StatusOr<ValidateResult> result = ValidateMeasurements({"calibrated.yaml", "held_out.csv"});
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/status.h"
#include "core/validation.h"

namespace hexcal::workflow {

struct ValidateRequest {
  std::string robot;         // robot file or preset name
  std::string measurements;  // measurements CSV: x,y,z,q1,q2,q3,L1..L6
};

struct ValidateResult {
  std::string robot, length_unit, measurements;
  ValidationReport report;
};

StatusOr<ValidateResult> ValidateMeasurements(const ValidateRequest& request);

nlohmann::json ToJson(const ValidateResult& result);
std::string FormatValidateSummary(const ValidateResult& result);

}  // namespace hexcal::workflow

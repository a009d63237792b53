// The verdict on a calibration (issue 15; docs/calibration.md, "Verdict"):
// good / acceptable / poor, with the findings that decide it. Each finding
// names an aspect, the figure and the threshold it was compared with (with
// units), what it means and, when not good, what to do next. The overall
// level is the worst finding's. The thresholds are the named constants of
// verdict_findings.h, each explained in docs/calibration.md.
//
//   Verdict verdict = MakeVerdict(report);  // report: results/report.json
//   std::cout << verdict.ToText();          // "Verdict: good" and one line per finding
//   json["verdict"] = verdict.ToJson();
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/validation.h"
#include "report/expected_error.h"
#include "report/verdict_findings.h"
#include "session/calibration_report.h"

namespace hexcal::workflow {

const char* VerdictLevelName(VerdictLevel level);  // "good", "acceptable", "poor"
// The colour the HTML report and the GUI show a level in: "#1b7a34" (green), amber, red.
const char* VerdictLevelColour(VerdictLevel level);

struct Verdict {
  VerdictLevel level = VerdictLevel::kGood;  // the worst finding's
  std::vector<Finding> findings;

  void Add(Finding finding);  // keeps `level` the worst
  // {"level", "findings": [{"aspect", "level", "figure", "threshold", "meaning", "advice"}]}
  nlohmann::json ToJson() const;
  // "Verdict: good" then one line per finding: level, aspect, figure, threshold, advice.
  std::string ToText() const;
};

Verdict MakeVerdict(const CalibrationReport& report, const std::optional<VerdictTruth>& truth = std::nullopt);

// `hexcal validate` on a file: the FK errors against what `expected` predicts.
Verdict MakeValidationVerdict(const ValidationReport& report, const ExpectedPoseError& expected,
                              const std::string& length_unit);

}  // namespace hexcal::workflow

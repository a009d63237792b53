#include "report/calibration_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "report/verdict_checks.h"

namespace hexcal::workflow {

namespace {

struct LevelStyle {
  const char* name;
  const char* colour;
};
// By VerdictLevel: green, amber, red, dark enough to read as text on white.
constexpr LevelStyle kLevelStyles[] = {{"good", "#1b7a34"}, {"acceptable", "#a86400"}, {"poor", "#c0262d"}};

}  // namespace

const char* VerdictLevelName(VerdictLevel level) { return kLevelStyles[static_cast<int>(level)].name; }
const char* VerdictLevelColour(VerdictLevel level) { return kLevelStyles[static_cast<int>(level)].colour; }

void Verdict::Add(Finding finding) {
  level = std::max(level, finding.level);
  findings.push_back(std::move(finding));
}

nlohmann::json Verdict::ToJson() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const Finding& f : findings) {
    rows.push_back({{"aspect", f.aspect},
                    {"level", VerdictLevelName(f.level)},
                    {"figure", f.figure},
                    {"threshold", f.threshold},
                    {"meaning", f.meaning},
                    {"advice", f.advice.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.advice)}});
  }
  return {{"level", VerdictLevelName(level)}, {"findings", rows}};
}

std::string Verdict::ToText() const {
  std::ostringstream out;
  out << "Verdict: " << VerdictLevelName(level) << "\n";
  for (const Finding& f : findings) {
    char head[64];
    std::snprintf(head, sizeof head, "  %-10s ", VerdictLevelName(f.level));
    out << head << f.aspect << ": " << f.figure << " (" << f.threshold << ")";
    if (!f.advice.empty()) out << "; " << f.advice;
    out << "\n";
  }
  return out.str();
}

Verdict MakeVerdict(const CalibrationReport& report, const std::optional<VerdictTruth>& truth) {
  Verdict verdict;
  verdict.Add(CheckHeldOut(report));
  if (report.noise) verdict.Add(CheckClosure(report));
  if (!report.legs.empty()) verdict.Add(CheckResiduals(report));
  if (report.noise) verdict.Add(CheckParameterSigmas(report));
  if (!report.parameters.empty()) verdict.Add(CheckParameterChanges(report));
  if (std::optional<Finding> camera = CheckCameraScale(report)) verdict.Add(*camera);
  if (std::optional<Finding> reflectors = CheckReflectorScale(report)) verdict.Add(*reflectors);
  if (truth) verdict.Add(CheckTruth(*truth));
  if (std::optional<Finding> conditioning = CheckConditioning(report)) verdict.Add(*conditioning);
  verdict.Add(CheckPoses(report));
  verdict.Add(CheckUnusableImages(report));
  verdict.Add(CheckOutliers(report));
  return verdict;
}

Verdict MakeValidationVerdict(const ValidationReport& report, const ExpectedPoseError& expected,
                              const std::string& length_unit) {
  Verdict verdict;
  PoseErrorStats stats{report.position.rms, report.position.max, report.orientation_deg.rms, report.orientation_deg.max,
                       report.failed};
  Finding fk = CheckFkErrors(stats, expected, length_unit, /*worst_image=*/"");
  // The file's rows, held out or not, and a robot that may be the nominal one.
  fk.aspect = "FK error";
  if (fk.level == VerdictLevel::kGood) {
    fk.meaning = "the robot's forward kinematics match these measured poses as well as their noise allows.";
  } else {
    fk.meaning = "the robot's forward kinematics miss these poses by more than the measurement noise explains.";
    fk.advice =
        "check that the robot file is the calibrated one and that --noise-* match the sensors; if so, "
        "calibrate again with more poses";
  }
  verdict.Add(fk);
  return verdict;
}

}  // namespace hexcal::workflow

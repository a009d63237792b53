#include "workflow/session_status.h"

#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>

#include "core/constraints.h"
#include "core/csv.h"
#include "core/session.h"
#include "session/readings_table.h"
#include "session/session_models.h"
#include "session/session_results.h"
#include "workflow/acquire_step.h"
#include "workflow/plan_captures.h"
#include "workflow/point_session.h"
#include "workflow/reading_check.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_measure.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

// "1 pose", "12 poses": the GUI's step list shows these sentences as they are.
std::string Count(size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// A plan is judged by its content against the robot as it is now: a pose the
// robot cannot reach (a new stroke, a moved joint) makes it stale, named with
// the constraint it breaks; a plan merely older than the robot file is not.
StepReport PlanStep(const std::string& dir, const StatusOr<Robot>& robot) {
  const std::string path = SessionPaths(dir).plan;
  std::error_code error;
  // symlink_status: a dangling link is a broken plan, named so, not a missing one.
  if (!fs::exists(fs::symlink_status(path, error)))
    return {"plan", StepStatus::kTodo, "no plan.csv: hexcal plan --out " + path};
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(path);
  if (!plan.ok()) return {"plan", StepStatus::kBroken, plan.status().message()};
  const std::string count = Count(plan->size(), "pose");
  if (!robot.ok()) return {"plan", StepStatus::kStale, count + ", not checked: the robot does not load"};
  int unreachable = 0;
  std::string first;
  for (size_t k = 0; k < plan->size(); ++k) {
    const ConstraintReport report = EvaluateConstraints(*robot, robot->PoseFromVector((*plan)[k]));
    if (report.feasible) continue;
    if (++unreachable == 1) first = "pose " + std::to_string(k + 1) + " breaks " + report.worst_label;
  }
  if (unreachable == 0) return {"plan", StepStatus::kDone, count + ", all reachable by the robot"};
  return {"plan", StepStatus::kStale,
          std::to_string(unreachable) + " of " + count + " unreachable by the robot as it is now (" + first +
              "): plan again"};
}

// How many poses of plan.csv are recorded: a row holds the pose it was
// commanded to (plan_captures.h), whatever its image's name; none without a plan.
int RecordedPlanPoses(const std::string& dir, const StatusOr<Robot>& robot, const SessionConfig& config, int* planned) {
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(SessionPaths(dir).plan);
  *planned = plan.ok() ? static_cast<int>(plan->size()) : 0;
  StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable(dir);
  if (!plan.ok() || !rows.ok() || !robot.ok()) return 0;
  const ReadingCheck check = MakeReadingCheck(*robot, config.noise);
  int recorded = 0;
  for (const int row : CapturesOfPlan(check, *plan, *rows)) recorded += row >= 0;
  return recorded;
}

// Readings are done when legs.csv loads; an acquisition of the plan begun and
// not finished (some pose_NNNN.png recorded, not all) is still to do.
StepReport ReadingsStep(const std::string& dir, const StatusOr<Robot>& robot, const SessionConfig& config,
                        const std::string& noun, std::vector<LegsRow>* rows) {
  const SessionPaths paths(dir);
  std::error_code error;
  if (!fs::exists(fs::symlink_status(paths.legs, error)))
    return {"readings", StepStatus::kTodo,
            "no legs.csv: acquire the planned poses (hexcal acquire) or enter the readings of each image"};
  StatusOr<std::vector<LegsRow>> legs = LoadSessionLegs(dir);
  if (!legs.ok()) return {"readings", StepStatus::kBroken, legs.status().message()};
  *rows = *legs;
  int held_out = 0;
  for (const LegsRow& row : *rows) held_out += row.holdout;
  const std::string count = Count(rows->size(), noun) + " with readings, " + std::to_string(held_out) + " held out";
  int planned = 0;
  const int recorded = RecordedPlanPoses(dir, robot, config, &planned);
  if (recorded > 0 && recorded < planned)
    return {"readings", StepStatus::kTodo,
            count + "; " + std::to_string(recorded) + " of " + std::to_string(planned) +
                " planned poses recorded: acquire the rest (hexcal acquire resumes)"};
  return {"readings", StepStatus::kDone, count};
}

StepReport MeasureStep(const std::string& dir, const std::vector<LegsRow>& rows, const ContentHashes* hashes) {
  if (rows.empty()) return {"measure", StepStatus::kTodo, "no images with readings yet"};
  std::vector<std::string> images;
  for (const LegsRow& row : rows) images.push_back(row.image);
  StatusOr<MeasureState> state = SessionMeasureState(dir, images, hashes);
  if (!state.ok()) return {"measure", StepStatus::kBroken, state.status().message()};
  if (state->to_measure.empty()) return {"measure", StepStatus::kDone, Count(images.size(), "image") + " measured"};
  const std::string count = std::to_string(state->to_measure.size()) + " of " + std::to_string(images.size());
  if (!state->reason.empty())
    return {"measure", StepStatus::kStale, count + " to measure again: " + state->reason};
  return {"measure", StepStatus::kTodo, count + " images not measured yet (calibrate --session measures them)"};
}

// A points session's Measure step: the points file loads and has every row's pose.
StepReport PointMeasureStep(const std::string& dir, const SessionConfig& config, const std::vector<LegsRow>& rows) {
  if (rows.empty()) return {"measure", StepStatus::kTodo, "no poses with readings yet"};
  StatusOr<PointFiles> files = SessionPointFiles(dir, config, /*with_noise_factor=*/false);
  StatusOr<std::string> described = DescribePointPoses(*files, rows);
  if (!described.ok()) return {"measure", StepStatus::kBroken, described.status().message()};
  return {"measure", StepStatus::kDone, *described};
}

std::string Figure(double value) {
  std::ostringstream out;
  out << std::setprecision(3) << value;
  return out.str();
}

void ResultSteps(const std::string& dir, const ContentHashes* hashes, SessionStatus* status,
                 StatusOr<SessionResults>* loaded) {
  std::error_code error;
  if (!fs::exists(CalibrationReportPath(dir), error)) {
    status->steps.push_back({"calibrate", StepStatus::kTodo, "no results: hexcal calibrate --session " + dir});
    status->steps.push_back({"validate", StepStatus::kTodo, "after calibrate"});
    return;
  }
  StatusOr<SessionResults>& results = *loaded;
  results = LoadSessionResults(dir, hashes);
  if (!results.ok()) {
    status->steps.push_back({"calibrate", StepStatus::kBroken, results.status().message()});
    status->steps.push_back({"validate", StepStatus::kTodo, "after calibrate"});
    return;
  }
  const CalibrationReport& report = results->report;
  const bool stale = !results->changed_inputs.empty();
  const std::string since = " (results of " + results->manifest.created + ")";
  status->steps.push_back(
      {"calibrate", stale ? StepStatus::kStale : StepStatus::kDone,
       stale ? ListNames(results->changed_inputs) + " changed since the results" + since + ": calibrate again"
             : Count(report.calibration_images, MeasurementNoun(report.instrument)) +
                   ", closure RMS " + Figure(report.closure_position_rms) + " " + report.length_unit + since});
  if (!report.validation) {
    status->steps.push_back({"validate", StepStatus::kTodo, "no image held out (holdout column of legs.csv)"});
    return;
  }
  const ValidationSummary& v = *report.validation;
  status->steps.push_back({"validate", stale ? StepStatus::kStale : StepStatus::kDone,
                           std::to_string(report.held_out_images) + " held out: position RMS " +
                               Figure(v.before.position_rms) + " -> " + Figure(v.after.position_rms) + " " +
                               report.length_unit});
}

}  // namespace

const StepReport* SessionStatus::Find(const std::string& step) const {
  for (const StepReport& report : steps)
    if (report.step == step) return &report;
  return nullptr;
}

const char* StepStatusName(StepStatus status) {
  switch (status) {
    case StepStatus::kDone:
      return "done";
    case StepStatus::kStale:
      return "stale";
    case StepStatus::kTodo:
      return "todo";
    case StepStatus::kBroken:
      return "broken";
  }
  return "";
}

StatusOr<SessionStatus> ReadSessionStatus(const std::string& dir) {
  StatusOr<SessionResults> results = Status::BadInput("no results");
  return ReadSessionStatus(dir, &results);
}

StatusOr<SessionStatus> ReadSessionStatus(const std::string& dir, StatusOr<SessionResults>* results,
                                          StatusOr<ContentHashes>* inputs) {
  *results = Status::BadInput("No results yet: run the Calibrate step.");
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  SessionStatus status;
  status.session = dir;
  StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
  status.steps.push_back(robot.ok() ? StepReport{"robot", StepStatus::kDone, robot->name}
                                    : StepReport{"robot", StepStatus::kBroken, robot.status().message()});
  status.steps.push_back(PlanStep(dir, robot));
  std::vector<LegsRow> rows;
  status.steps.push_back(
      ReadingsStep(dir, robot, *config, MeasurementNoun(config->instrument), &rows));
  // Every input hashed once, for the measure record and the results manifest
  // both (images are most of it); on an error each hashes what it needs and
  // reports its own error.
  const StatusOr<ContentHashes> hashes = HashSessionInputs(dir);
  const ContentHashes* known = hashes.ok() ? &*hashes : nullptr;
  if (inputs != nullptr) *inputs = hashes;
  status.steps.push_back(config->instrument == Instrument::kPoints ? PointMeasureStep(dir, *config, rows)
                                                                   : MeasureStep(dir, rows, known));
  ResultSteps(dir, known, &status, results);
  return status;
}

// {"session", "steps": {"robot": "done", ...}, "why": {"robot": "...", ...}}:
// a program reads the states by step name, a person the sentences.
nlohmann::json ToJson(const SessionStatus& status) {
  nlohmann::json steps = nlohmann::json::object();
  nlohmann::json why = nlohmann::json::object();
  for (const StepReport& step : status.steps) {
    steps[step.step] = StepStatusName(step.status);
    why[step.step] = step.detail;
  }
  return {{"session", status.session}, {"steps", steps}, {"why", why}};
}

std::string FormatSessionStatus(const SessionStatus& status) {
  std::ostringstream out;
  out << "session " << status.session << "\n";
  for (const StepReport& step : status.steps)
    out << "  " << std::left << std::setw(10) << step.step << std::setw(7) << StepStatusName(step.status) << " "
        << step.detail << "\n";
  return out.str();
}

}  // namespace hexcal::workflow

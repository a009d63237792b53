#include "ui/session_state.h"

#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <algorithm>
#include <filesystem>

#include "workflow/plan_step.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_measure.h"
#include "workflow/session_results.h"
#include "core/csv.h"
#include "core/robot_io.h"
#include "vision/measure.h"

namespace hexcal::ui {
namespace {

namespace fs = std::filesystem;

QDateTime Modified(const std::string& path) { return QFileInfo(QString::fromStdString(path)).lastModified(); }
bool Exists(const std::string& path) { return QFileInfo::exists(QString::fromStdString(path)); }

}  // namespace

const char* StepName(Step step) {
  switch (step) {
    case Step::kRobot:
      return "Robot";
    case Step::kPlan:
      return "Plan";
    case Step::kMeasure:
      return "Measure";
    case Step::kCalibrate:
      return "Calibrate";
    case Step::kValidate:
      return "Validate";
  }
  return "";
}

SessionState::SessionState(QObject* parent) : QObject(parent) {
  constexpr int kSettleMs = 300;
  reload_timer_.setSingleShot(true);
  reload_timer_.setInterval(kSettleMs);
  connect(&watcher_, &QFileSystemWatcher::directoryChanged, this, [this] { reload_timer_.start(); });
  connect(&watcher_, &QFileSystemWatcher::fileChanged, this, [this] { reload_timer_.start(); });
  connect(&reload_timer_, &QTimer::timeout, this, &SessionState::Reload);
}

// The folder itself (atomic writes and the swap of results/ are renames in
// it), images/ and results/; re-armed after each load, since a swapped
// results/ is a new folder.
void SessionState::Watch() {
  if (!watcher_.directories().isEmpty()) watcher_.removePaths(watcher_.directories());
  if (!watcher_.files().isEmpty()) watcher_.removePaths(watcher_.files());
  const SessionPaths paths = Paths();
  for (const std::string& path : {paths.dir, paths.images, paths.results})
    if (QFileInfo(QString::fromStdString(path)).isDir()) watcher_.addPath(QString::fromStdString(path));
  // Files written in place (`>>`, an editor) change no folder entry.
  for (const std::string& path : {paths.legs, paths.plan, paths.config, paths.measurements})
    if (QFileInfo(QString::fromStdString(path)).isFile()) watcher_.addPath(QString::fromStdString(path));
}

// Measure is done when every image with readings has a row measured with the
// camera, target and image file as they are now (workflow/session_measure.h).
void SessionState::LoadMeasureState() {
  measure_state_ = StepState::kTodo;
  measure_note_.clear();
  if (legs_.empty()) return;
  std::vector<std::string> images;
  for (const LegsRow& row : legs_) images.push_back(row.image);
  StatusOr<workflow::MeasureState> state = workflow::SessionMeasureState(dir_.toStdString(), images);
  if (!state.ok()) {
    measure_note_ = QString::fromStdString(state.status().message());
    return;
  }
  if (state->to_measure.empty()) {
    measure_state_ = StepState::kDone;
  } else if (!state->reason.empty()) {
    measure_state_ = StepState::kStale;
    measure_note_ = QString::fromStdString(state->reason);
  }
}

// Calibrate and Validate are done when results/ is one whole unit made from
// the inputs as they are now (workflow/session_results.h).
void SessionState::LoadResultsState() {
  results_state_ = StepState::kTodo;
  results_note_.clear();
  results_ = Status::Error("No results yet: run the Calibrate step.");
  std::error_code error;
  if (!fs::exists(workflow::CalibrationReportPath(dir_.toStdString()), error)) return;
  results_ = workflow::LoadSessionResults(dir_.toStdString());
  if (!results_.ok()) {
    results_note_ = QString::fromStdString(results_.status().message());
    return;
  }
  if (!results_->changed_inputs.empty()) {
    results_state_ = StepState::kStale;
    results_note_ = QString::fromStdString(workflow::ListNames(results_->changed_inputs)) +
                    " changed since the results were computed: calibrate again.";
    return;
  }
  results_state_ = StepState::kDone;
}

std::string SessionState::Resolve(const std::string& name) const {
  return workflow::ResolveSessionFile(dir_.toStdString(), name);
}

Status SessionState::LoadAll(const QString& dir) {
  // Resolve() reads dir_: point it at the new folder, and back if it does not load.
  const QString previous = dir_;
  dir_ = dir;
  const auto fail = [&](const Status& status) {
    dir_ = previous;
    return status;
  };
  StatusOr<SessionConfig> config = LoadSessionConfig(dir.toStdString());
  if (!config.ok()) return fail(config.status());
  StatusOr<Robot> robot = LoadRobot(Resolve(config->robot));
  if (!robot.ok()) return fail(robot.status());
  config_ = *config;
  robot_ = *robot;
  // Camera and target are needed from the Measure step on: a session may be
  // opened to plan before they exist, so their errors show there, not here.
  StatusOr<Camera> camera = LoadCamera(Resolve(config_.camera));
  camera_ = camera.ok() ? std::optional<Camera>(*camera) : std::nullopt;
  StatusOr<Target> target = LoadTarget(Resolve(config_.target));
  target_ = target.ok() ? std::optional<Target>(*target) : std::nullopt;
  plan_.clear();
  if (Exists(Paths().plan)) {
    StatusOr<std::vector<Vector6d>> plan = LoadPoses(Paths().plan);
    if (plan.ok()) plan_ = *plan;
  }
  legs_.clear();
  legs_error_.clear();
  if (Exists(Paths().legs)) {
    StatusOr<std::vector<LegsRow>> legs = LoadSessionLegs(dir.toStdString());
    if (legs.ok()) {
      legs_ = *legs;
    } else {
      legs_error_ = QString::fromStdString(legs.status().message());
    }
  }
  LoadMeasureState();
  LoadResultsState();
  Watch();
  return Status::Ok();
}

Status SessionState::Open(const QString& dir) {
  Status loaded = LoadAll(QDir(dir).absolutePath());
  if (loaded.ok()) emit Changed();
  return loaded;
}

Status SessionState::Create(const QString& dir, const SessionConfig& config) {
  if (Status made = InitSession(dir.toStdString(), config); !made.ok()) return made;
  return Open(dir);
}

void SessionState::Reload() {
  if (!IsOpen()) return;
  LoadAll(dir_);
  emit Changed();
}

// Every edit: applied to the files on disk, then everything reloaded from them.
workflow::EditOutcome SessionState::ApplyEdit(
    bool overwrite, const std::function<workflow::EditOutcome(const workflow::EditOptions&)>& edit) {
  workflow::EditOptions options;
  options.overwrite = overwrite;
  const workflow::EditOutcome done = edit(options);
  Reload();
  return done;
}

workflow::EditOutcome SessionState::SetPlan(const std::vector<Vector6d>& poses, bool overwrite,
                                            const std::vector<Vector6d>* seen) {
  return ApplyEdit(overwrite, [&](const workflow::EditOptions& options) {
    return workflow::ApplyPlanEdit(dir_.toStdString(), seen ? *seen : plan_, poses, options);
  });
}

workflow::EditOutcome SessionState::EditLegs(const workflow::LegsEdit& edit, bool overwrite) {
  return ApplyEdit(overwrite, [&](const workflow::EditOptions& options) {
    return workflow::ApplyLegsEdit(dir_.toStdString(), edit, options);
  });
}

workflow::EditOutcome SessionState::RecordCapture(const std::string& frame_file, const LegsRow& row, bool overwrite) {
  return ApplyEdit(overwrite, [&](const workflow::EditOptions& options) {
    return workflow::RecordCapture(dir_.toStdString(), frame_file, row, options);
  });
}

workflow::EditOutcome SessionState::SetCamera(const std::string& camera_name, bool overwrite) {
  return ApplyEdit(overwrite, [&](const workflow::EditOptions& options) {
    return workflow::ApplyCameraEdit(dir_.toStdString(), config_.camera, camera_name, options);
  });
}

std::vector<QString> SessionState::ImageFiles() const {
  std::vector<QString> files;
  StatusOr<std::vector<std::string>> listed = ListImages(Paths().images);
  if (listed.ok())
    for (const std::string& file : *listed) files.push_back(QString::fromStdString(file));
  return files;
}

StepState SessionState::State(Step step) const {
  if (!IsOpen()) return StepState::kTodo;
  const SessionPaths paths = Paths();
  switch (step) {
    case Step::kRobot:
      return StepState::kDone;
    case Step::kPlan:
      if (!Exists(paths.plan)) return StepState::kTodo;
      // A plan made for another robot file is stale.
      return Modified(paths.plan) < Modified(Resolve(config_.robot)) ? StepState::kStale : StepState::kDone;
    case Step::kMeasure:
      return measure_state_;
    case Step::kCalibrate:
    case Step::kValidate:
      if (step == Step::kValidate && results_state_ != StepState::kTodo &&
          std::none_of(legs_.begin(), legs_.end(), [](const LegsRow& r) { return r.holdout; }))
        return StepState::kTodo;  // nothing held out: no validation
      return results_state_;
  }
  return StepState::kTodo;
}

}  // namespace hexcal::ui

#include "ui/session_state.h"

#include <QDir>
#include <QFileInfo>
#include <QStringList>

#include "workflow/plan_step.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_init.h"
#include "workflow/session_results.h"
#include "core/csv.h"
#include "core/robot_io.h"
#include "vision/measure.h"

namespace hexcal::ui {
namespace {

bool Exists(const std::string& path) { return QFileInfo::exists(QString::fromStdString(path)); }

}  // namespace

const char* StepName(Step step) {
  switch (step) {
    case Step::kRobot:
      return "Robot";
    case Step::kPlan:
      return "Plan";
    case Step::kAcquire:
      return "Acquire";
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
  for (const std::string& path : {paths.legs, paths.plan, paths.config, paths.camera_poses})
    if (QFileInfo(QString::fromStdString(path)).isFile()) watcher_.addPath(QString::fromStdString(path));
}

// Every step's state at once, from the files' contents (workflow/session_status.h);
// results/ and study/ come back loaded for the panels, the inputs hashed once.
void SessionState::LoadStatus() {
  const std::string dir = dir_.toStdString();
  StatusOr<workflow::ContentHashes> inputs = Status::Error("not hashed");
  StatusOr<workflow::SessionStatus> status = workflow::ReadSessionStatus(dir, &results_, &inputs);
  status_ = status.ok() ? std::optional<workflow::SessionStatus>(*status) : std::nullopt;
  study_ = workflow::HasSessionStudy(dir) ? workflow::LoadSessionStudy(dir, inputs.ok() ? &*inputs : nullptr)
                                          : StatusOr<workflow::SessionStudy>(Status::Error(kNoStudyYet));
}

QString SessionState::InSession(const QString& text) const {
  if (dir_.isEmpty()) return text;
  QString shorter = text;
  if (!dir_.endsWith('/')) shorter.replace(dir_ + "/", QString());  // the folder as opened
  return shorter.replace(QDir::cleanPath(dir_) + "/", QString());
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
  LoadStatus();
  Watch();
  return Status::Ok();
}

Status SessionState::Open(const QString& dir) {
  const QString previous = dir_;
  Status loaded = LoadAll(QDir(dir).absolutePath());
  if (!loaded.ok()) return loaded;
  if (dir_ != previous) emit Switched();
  emit Changed();
  return loaded;
}

Status SessionState::Create(const QString& dir, const SessionConfig& config) {
  // Nothing is created when the robot, camera or target does not load (as the CLI).
  if (Status made = workflow::CreateSession(dir.toStdString(), config); !made.ok()) return made;
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

workflow::EditOutcome SessionState::RecordCaptureBytes(const std::string& image_bytes, const LegsRow& row,
                                                       bool overwrite) {
  return ApplyEdit(overwrite, [&](const workflow::EditOptions& options) {
    return workflow::RecordCaptureBytes(dir_.toStdString(), image_bytes, row, options);
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

namespace {

// The workflow step (session_status.h) a GUI step shows: Acquire is `readings`.
const char* WorkflowStep(Step step) {
  switch (step) {
    case Step::kRobot:
      return "robot";
    case Step::kPlan:
      return "plan";
    case Step::kAcquire:
      return "readings";
    case Step::kMeasure:
      return "measure";
    case Step::kCalibrate:
      return "calibrate";
    case Step::kValidate:
      return "validate";
  }
  return "";
}

}  // namespace

StepState SessionState::State(Step step) const {
  const workflow::StepReport* report = IsOpen() && status_ ? status_->Find(WorkflowStep(step)) : nullptr;
  return report != nullptr ? report->status : StepState::kTodo;
}

QString SessionState::Why(Step step) const {
  if (!IsOpen()) return "no session open";
  if (!status_) return "the session's status could not be read";
  const workflow::StepReport* report = status_->Find(WorkflowStep(step));
  return report != nullptr ? QString::fromStdString(report->detail) : QString();
}

QString SessionState::ResultsNote() const {
  const StepState state = State(Step::kCalibrate);
  return state == StepState::kStale || state == StepState::kBroken ? Why(Step::kCalibrate) : QString();
}

}  // namespace hexcal::ui

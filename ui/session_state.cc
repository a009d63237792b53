#include "ui/session_state.h"

#include <sys/stat.h>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSet>
#include <QStringList>

#include "core/csv.h"
#include "session/session_models.h"
#include "session/session_results.h"
#include "session/session_study.h"
#include "vision/measure.h"
#include "workflow/plan_step.h"
#include "workflow/point_session.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_init.h"

namespace hexcal::ui {
namespace {

bool Exists(const std::string& path) { return QFileInfo::exists(QString::fromStdString(path)); }

// A file's identity: the watch of a path follows the inode it was added on.
std::string Inode(const QString& path) {
  struct stat info {};
  if (::stat(QFile::encodeName(path).constData(), &info) != 0) return "-";
  return std::to_string(info.st_dev) + ":" + std::to_string(info.st_ino);
}

// What changes with any write, rename, deletion or new entry, without
// reading the content: inode, size, modification and change times (ns).
std::string Stamp(const QString& path) {
  struct stat info {};
  if (::stat(QFile::encodeName(path).constData(), &info) != 0) return path.toStdString() + " -\n";
  return path.toStdString() + " " + std::to_string(info.st_dev) + ":" + std::to_string(info.st_ino) + " " +
         std::to_string(info.st_size) + " " + std::to_string(info.st_mtim.tv_sec) + "." +
         std::to_string(info.st_mtim.tv_nsec) + " " + std::to_string(info.st_ctim.tv_sec) + "." +
         std::to_string(info.st_ctim.tv_nsec) + "\n";
}

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
  constexpr int kSettleMs = 150;
  constexpr int kPollMs = 2000;
  reload_timer_.setSingleShot(true);
  reload_timer_.setInterval(kSettleMs);
  connect(&watcher_, &QFileSystemWatcher::directoryChanged, this, [this] { reload_timer_.start(); });
  connect(&watcher_, &QFileSystemWatcher::fileChanged, this, [this] { reload_timer_.start(); });
  connect(&reload_timer_, &QTimer::timeout, this, &SessionState::Reload);
  poll_timer_.setInterval(kPollMs);
  connect(&poll_timer_, &QTimer::timeout, this, &SessionState::ReloadIfChanged);
}

// Folders: the session's (atomic writes and the swap of results/ are renames
// in it), images/, results/, study/, and the folder of each robot, camera and
// target file (a points session: robot, points and reflector file) wherever
// it is (a file replaced or made again there is a new entry). Files, for what
// is written in place (cp over it, `>>`, an editor that keeps the inode):
// session.yaml, plan.csv, legs.csv, the measurements, noise_check.json, the
// files session.yaml names, and every file of images/, results/ and study/.
// A name that is a preset has no file; a file named in session.yaml that is
// missing is watched for through its folder.
SessionState::DiskPaths SessionState::Dependencies(const SessionConfig* config) const {
  DiskPaths paths;
  QSet<QString> seen;
  const auto add = [&](QStringList* list, const QString& path) {
    const QString clean = QDir::cleanPath(path);
    if (!seen.contains(clean)) {
      seen.insert(clean);
      list->append(clean);
    }
  };
  const SessionPaths session = Paths();
  const QString dir = QString::fromStdString(session.dir);
  add(&paths.folders, dir);
  for (const std::string& name : {session.config, session.plan, session.legs, session.camera_poses})
    add(&paths.files, QString::fromStdString(name));
  for (const char* name : {"camera_poses.json", "plan_history.csv", kNoiseCheckFile})
    add(&paths.files, QDir(dir).filePath(name));
  for (const std::string& folder : {session.images, session.results, workflow::StudyFolderPath(session.dir)}) {
    const QDir listed(QString::fromStdString(folder));
    if (!listed.exists()) continue;
    add(&paths.folders, listed.path());
    for (const QString& file : listed.entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name))
      add(&paths.files, listed.filePath(file));
  }
  if (config == nullptr) return paths;
  const bool points = config->instrument == Instrument::kPoints;
  for (const std::string* name : {&config->robot, points ? &config->points : &config->camera,
                                  points ? &config->reflectors : &config->target}) {
    if (name->empty()) continue;  // no reflector file: they are estimated
    const QString in_session = QDir(dir).filePath(QString::fromStdString(*name));
    const QFileInfo resolved(QString::fromStdString(Resolve(*name)));
    // The file (a symbolic link is watched through to its target), its folder and its target's folder.
    for (const QFileInfo& file : {resolved, QFileInfo(resolved.canonicalFilePath())}) {
      if (!file.isFile()) continue;
      add(&paths.files, file.absoluteFilePath());
      add(&paths.folders, file.absolutePath());
    }
    // Missing: where it would come back (in the session, or at its absolute path).
    const QFileInfo wanted(QFileInfo(QString::fromStdString(*name)).isAbsolute() ? QString::fromStdString(*name)
                                                                                 : in_session);
    if (!resolved.isFile() && QFileInfo(wanted.absolutePath()).isDir()) add(&paths.folders, wanted.absolutePath());
  }
  return paths;
}

void SessionState::Watch(const DiskPaths& paths) {
  stamps_.clear();
  for (const QStringList* list : {&paths.folders, &paths.files})
    for (const QString& path : *list) stamps_ += Stamp(path);
  if (!watcher_enabled_) return;
  QSet<QString> wanted;
  for (const QString& path : paths.folders)
    if (QFileInfo(path).isDir()) wanted.insert(path);
  for (const QString& path : paths.files)
    if (QFileInfo(path).isFile()) wanted.insert(path);
  QStringList drop;
  for (const QString& path : watcher_.directories())
    if (!wanted.contains(path)) drop << path;
  // A file replaced by a rename over it whose old inode lives on (a hard link
  // elsewhere) keeps its watch on the old inode: renewed here.
  for (const QString& path : watcher_.files())
    if (!wanted.contains(path) || watched_inode_[path] != Inode(path)) drop << path;
  if (!drop.isEmpty()) watcher_.removePaths(drop);
  for (const QString& path : drop) watched_inode_.erase(path);
  QSet<QString> watched;
  for (const QStringList& list : {watcher_.directories(), watcher_.files()})
    for (const QString& path : list) watched.insert(path);
  QStringList add;
  for (const QString& path : wanted)
    if (!watched.contains(path)) add << path;
  const QStringList failed = add.isEmpty() ? QStringList() : watcher_.addPaths(add);
  for (const QString& path : add)
    if (!failed.contains(path) && QFileInfo(path).isFile()) watched_inode_[path] = Inode(path);
  // Beyond the system's watch limit: the stamps are compared every few seconds instead.
  if (failed.isEmpty()) {
    poll_timer_.stop();
  } else if (!poll_timer_.isActive()) {
    poll_timer_.start();
  }
}

QStringList SessionState::WatchedPaths() const { return watcher_.directories() + watcher_.files(); }

void SessionState::SetWatcherEnabled(bool enabled) {
  watcher_enabled_ = enabled;
  if (!watcher_.directories().isEmpty()) watcher_.removePaths(watcher_.directories());
  if (!watcher_.files().isEmpty()) watcher_.removePaths(watcher_.files());
  watched_inode_.clear();
  poll_timer_.stop();
  if (enabled && IsOpen()) Reload();
}

bool SessionState::ReloadIfChanged() {
  if (!IsOpen()) return false;
  const std::string before = stamps_;
  StatusOr<SessionConfig> config = LoadSessionConfig(dir_.toStdString());
  const DiskPaths paths = Dependencies(config.ok() ? &*config : nullptr);
  std::string now;
  for (const QStringList* list : {&paths.folders, &paths.files})
    for (const QString& path : *list) now += Stamp(path);
  if (now == before) return false;
  Reload();
  return true;
}

// Every step's state at once, from the files' contents (workflow/session_status.h);
// results/ and study/ come back loaded for the panels, the inputs hashed once.
void SessionState::LoadStatus() {
  const std::string dir = dir_.toStdString();
  StatusOr<workflow::ContentHashes> inputs = Status::BadInput("not hashed");
  StatusOr<workflow::SessionStatus> status = workflow::ReadSessionStatus(dir, &results_, &inputs);
  status_ = status.ok() ? std::optional<workflow::SessionStatus>(*status) : std::nullopt;
  study_ = workflow::HasSessionStudy(dir) ? workflow::LoadSessionStudy(dir, inputs.ok() ? &*inputs : nullptr)
                                          : StatusOr<workflow::SessionStudy>(Status::BadInput(kNoStudyYet));
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

void SessionState::LoadAll(const QString& dir) {
  dir_ = dir;
  // Watched first, then read: a change made while the files are read is seen
  // by the watch, or else by ReloadIfChanged's stamps, taken before reading.
  StatusOr<SessionConfig> config = LoadSessionConfig(dir.toStdString());
  Watch(Dependencies(config.ok() ? &*config : nullptr));
  load_error_.clear();
  if (!config.ok()) {
    // The open session's session.yaml went away or broke: every step is
    // broken with its message (the status's error) until it loads again.
    load_error_ = QString::fromStdString(config.status().message());
    status_.reset();
    results_ = config.status();
    study_ = config.status();
    return;
  }
  config_ = *config;
  // The robot as it now is, or the last that loaded (the status says why not).
  StatusOr<Robot> robot = workflow::LoadSessionRobot(dir.toStdString(), config_);
  if (robot.ok()) robot_ = *robot;
  // Camera and target are needed from the Measure step on: a session may be
  // opened to plan before they exist, so their errors show there, not here.
  // A points session has neither.
  camera_.reset();
  target_.reset();
  if (config_.instrument == Instrument::kCamera) {
    StatusOr<Camera> camera = LoadCamera(Resolve(config_.camera));
    if (camera.ok()) camera_ = *camera;
    StatusOr<Target> target = LoadTarget(Resolve(config_.target));
    if (target.ok()) target_ = *target;
  }
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
}

Status SessionState::Open(const QString& dir) {
  // The folder must hold a session whose robot loads; once open, whatever
  // fails to load later is shown as the status says (Reload).
  const QString absolute = QDir(dir).absolutePath();
  StatusOr<SessionConfig> config = LoadSessionConfig(absolute.toStdString());
  if (!config.ok()) return config.status();
  StatusOr<Robot> robot = workflow::LoadSessionRobot(absolute.toStdString(), *config);
  if (!robot.ok()) return robot.status();
  const QString previous = dir_;
  LoadAll(absolute);
  if (dir_ != previous) emit Switched();
  emit Changed();
  return Status::Ok();
}

Status SessionState::Create(const QString& dir, const SessionConfig& config) {
  // Nothing is created when the robot, camera or target does not load (as the CLI).
  if (Status made = workflow::CreateSession(dir.toStdString(), config); !made.ok()) return made;
  return Open(dir);
}

void SessionState::Reload() {
  if (!IsOpen()) return;
  reload_timer_.stop();  // this reload reads what the pending one would
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
  if (IsOpen() && !load_error_.isEmpty()) return StepState::kBroken;
  const workflow::StepReport* report = IsOpen() && status_ ? status_->Find(WorkflowStep(step)) : nullptr;
  return report != nullptr ? report->status : StepState::kTodo;
}

QString SessionState::Why(Step step) const {
  if (!IsOpen()) return "no session open";
  if (!load_error_.isEmpty()) return load_error_;
  if (!status_) return "the session's status could not be read";
  const workflow::StepReport* report = status_->Find(WorkflowStep(step));
  return report != nullptr ? QString::fromStdString(report->detail) : QString();
}

QString SessionState::ResultsNote() const {
  const StepState state = State(Step::kCalibrate);
  return state == StepState::kStale || state == StepState::kBroken ? Why(Step::kCalibrate) : QString();
}

}  // namespace hexcal::ui

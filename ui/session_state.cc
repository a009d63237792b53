#include "ui/session_state.h"

#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <algorithm>
#include <filesystem>

#include "workflow/plan_step.h"
#include "workflow/session_calibrate.h"
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

SessionState::SessionState(QObject* parent) : QObject(parent) {}

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

Status SessionState::Save() {
  if (!IsOpen()) return Status::Error("no session is open");
  if (Status s = SaveSessionConfig(dir_.toStdString(), config_); !s.ok()) return s;
  if (!plan_.empty()) return workflow::WritePlanCsv(Paths().plan, PlanningModel{robot_, std::nullopt, std::nullopt}, plan_);
  return Status::Ok();
}

Status SessionState::SetPlan(const std::vector<Vector6d>& poses) {
  plan_ = poses;
  Status written = Status::Ok();
  if (poses.empty()) {
    std::error_code error;
    fs::remove(Paths().plan, error);
  } else {
    written = workflow::WritePlanCsv(Paths().plan, PlanningModel{robot_, std::nullopt, std::nullopt}, poses);
  }
  emit Changed();
  return written;
}

Status SessionState::SetLegs(const std::vector<LegsRow>& rows) {
  std::vector<std::vector<std::string>> cells;
  for (const LegsRow& row : rows) {
    std::vector<std::string> line{row.image};
    for (int i = 0; i < kNumLegs; ++i) line.push_back(FormatNumber(row.legs[i]));
    line.push_back(row.holdout ? "1" : "0");
    cells.push_back(line);
  }
  Status written = WriteCsv(Paths().legs, {"image", "L1", "L2", "L3", "L4", "L5", "L6", "holdout"}, cells);
  LoadAll(dir_);
  emit Changed();
  return written;
}

Status SessionState::SetCamera(const std::string& camera_name) {
  config_.camera = camera_name;
  if (Status s = SaveSessionConfig(dir_.toStdString(), config_); !s.ok()) return s;
  Reload();
  return Status::Ok();
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
  const std::string report = (fs::path(paths.results) / "report.json").string();
  switch (step) {
    case Step::kRobot:
      return StepState::kDone;
    case Step::kPlan:
      if (!Exists(paths.plan)) return StepState::kTodo;
      // A plan made for another robot file is stale.
      return Modified(paths.plan) < Modified(Resolve(config_.robot)) ? StepState::kStale : StepState::kDone;
    case Step::kMeasure: {
      if (!Exists(paths.measurements) || legs_.empty()) return StepState::kTodo;
      for (const QString& image : ImageFiles())
        if (Modified(paths.measurements) < QFileInfo(image).lastModified()) return StepState::kStale;
      return StepState::kDone;
    }
    case Step::kCalibrate:
    case Step::kValidate: {
      if (!Exists(report)) return StepState::kTodo;
      const QDateTime made = Modified(report);
      if ((Exists(paths.legs) && made < Modified(paths.legs)) ||
          (Exists(paths.measurements) && made < Modified(paths.measurements)))
        return StepState::kStale;
      if (step == Step::kValidate &&
          std::none_of(legs_.begin(), legs_.end(), [](const LegsRow& r) { return r.holdout; }))
        return StepState::kTodo;  // nothing held out: no validation
      return StepState::kDone;
    }
  }
  return StepState::kTodo;
}

}  // namespace hexcal::ui

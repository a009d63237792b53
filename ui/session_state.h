// The open session as the panels see it: the folder (core/session.h), the
// nominal robot, camera and target it names, the plan and the readings.
//
// Everything the operator records is written to the folder at once (plan.csv,
// legs.csv, images/): the folder is the autosave, so nothing is lost if the
// application dies. Panels change the session only through this class, which
// then emits Changed() so that every panel and the step list refresh.
#pragma once

#include <QObject>
#include <QString>
#include <optional>
#include <vector>

#include "core/robot.h"
#include "core/session.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::ui {

enum class StepState { kTodo, kDone, kStale };

enum class Step { kRobot, kPlan, kMeasure, kCalibrate, kValidate };
constexpr int kNumSteps = 5;
const char* StepName(Step step);  // "Robot", "Plan", ...

class SessionState : public QObject {
  Q_OBJECT
 public:
  explicit SessionState(QObject* parent = nullptr);

  // Loads DIR/session.yaml and what it names; the message says what to fix.
  Status Open(const QString& dir);
  Status Create(const QString& dir, const SessionConfig& config);
  // Rewrites session.yaml and plan.csv (both are also written on every change).
  Status Save();
  // Re-reads the files after a step wrote them (measurements, results).
  void Reload();

  bool IsOpen() const { return !dir_.isEmpty(); }
  const QString& Dir() const { return dir_; }
  SessionPaths Paths() const { return SessionPaths(dir_.toStdString()); }
  const SessionConfig& Config() const { return config_; }
  const Robot& NominalRobot() const { return robot_; }
  const std::optional<Camera>& SessionCamera() const { return camera_; }
  const std::optional<Target>& SessionTarget() const { return target_; }
  // Full path of a name in session.yaml (robot, camera, target).
  std::string Resolve(const std::string& name) const;

  const std::vector<Vector6d>& Plan() const { return plan_; }
  // Replaces the plan and writes plan.csv.
  Status SetPlan(const std::vector<Vector6d>& poses);

  // legs.csv rows; `legs_error` is why the file does not load, if it does not.
  const std::vector<LegsRow>& Legs() const { return legs_; }
  const QString& LegsError() const { return legs_error_; }
  // Writes legs.csv (image, L1..L6, holdout) with these rows.
  Status SetLegs(const std::vector<LegsRow>& rows);
  std::vector<QString> ImageFiles() const;  // full paths, sorted

  StepState State(Step step) const;
  // Points the session at another camera file (intrinsics step).
  Status SetCamera(const std::string& camera_name);

 signals:
  void Changed();

 private:
  Status LoadAll(const QString& dir);

  QString dir_;
  SessionConfig config_;
  Robot robot_;
  std::optional<Camera> camera_;
  std::optional<Target> target_;
  std::vector<Vector6d> plan_;
  std::vector<LegsRow> legs_;
  QString legs_error_;
};

}  // namespace hexcal::ui

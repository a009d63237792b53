// The open session as the panels see it: the folder (core/session.h), the
// nominal robot, camera and target it names, the plan and the readings.
//
// Everything the operator records is written to the folder at once (plan.csv,
// legs.csv, images/): the folder is the autosave, so nothing is lost if the
// application dies. An edit is applied to the file as it is on disk, under the
// session lock (workflow/session_edits.h), never by writing back a copy held
// in memory; a conflict comes back to the caller to ask the operator. Every
// file the status depends on is watched, wherever it lives (docs/gui.md, "How
// the window notices changes"): what other programs write is reloaded and
// shown. Panels change the session only through this class, which then emits
// Changed() so that every panel and the step list refresh.
//
//   SessionState session;
//   if (Status s = session.Open("build/demo"); !s.ok()) ShowError(window, "Open", ...);
//   connect(&session, &SessionState::Changed, panel, &RobotPanel::Refresh);
#pragma once

#include <QFileSystemWatcher>
#include <QObject>
#include <QString>
#include <QTimer>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/robot.h"
#include "core/session.h"
#include "session/session_results.h"
#include "session/session_study.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/session_edits.h"
#include "workflow/session_status.h"

namespace hexcal::ui {

// workflow::StepStatus itself: the step list shows exactly what `hexcal
// session status` prints.
using StepState = workflow::StepStatus;

enum class Step { kRobot, kPlan, kAcquire, kMeasure, kCalibrate, kValidate };
constexpr int kNumSteps = 6;
const char* StepName(Step step);  // "Robot", "Plan", "Acquire", ...

// Study() of a session without study/.
constexpr const char* kNoStudyYet = "No section 8 study yet: run it here (or hexcal study).";

class SessionState : public QObject {
  Q_OBJECT
 public:
  explicit SessionState(QObject* parent = nullptr);

  // Loads DIR/session.yaml and what it names; the message says what to fix.
  Status Open(const QString& dir);
  Status Create(const QString& dir, const SessionConfig& config);
  // Re-reads the files after a step wrote them (measurements, results), or
  // another program did (the watch calls it), and before an action that uses
  // the status (calibrate, export, report). Of an open session whose
  // session.yaml no longer loads, every step is then broken with the reason,
  // and its robot, plan and readings stay as last read.
  void Reload();
  // Reload() if a file or folder the status depends on is not as it was when
  // last read (its inode, size, modification and change times: nothing is
  // hashed); the window calls it when it gains focus, for what a watcher
  // misses (a network file system). True when it reloaded.
  bool ReloadIfChanged();
  // The files and folders watched now (the robot, camera and target files, or
  // a points session's points and reflector files, and their folders wherever
  // they are, noise_check.json, every file of images/, results/, study/).
  QStringList WatchedPaths() const;
  // Tests: the watcher off, as on a file system that reports no change.
  void SetWatcherEnabled(bool enabled);

  bool IsOpen() const { return !dir_.isEmpty(); }
  const QString& Dir() const { return dir_; }
  SessionPaths Paths() const { return SessionPaths(dir_.toStdString()); }
  const SessionConfig& Config() const { return config_; }
  // A points session (docs/session.md): poses from a tracker's points file,
  // legs.csv keyed by `pose`, no images, camera or target.
  bool IsPointsSession() const { return IsOpen() && config_.instrument == Instrument::kPoints; }
  // What legs.csv's rows are: "pose" in a points session, else "image".
  QString RowNoun() const { return IsPointsSession() ? "pose" : "image"; }
  const Robot& NominalRobot() const { return robot_; }
  const std::optional<Camera>& SessionCamera() const { return camera_; }
  const std::optional<Target>& SessionTarget() const { return target_; }
  // Full path of a name in session.yaml (robot, camera, target).
  std::string Resolve(const std::string& name) const;
  // `text` with the session folder's path taken out of the paths it quotes
  // ("images/a.png", not "/home/…/run1/images/a.png"): shorter on screen.
  QString InSession(const QString& text) const;

  const std::vector<Vector6d>& Plan() const { return plan_; }
  // plan.csv becomes `poses`, unless it changed on disk since it was shown
  // (a conflict; `overwrite` applies it anyway).
  // `seen` is the plan the change started from (the one shown, by default).
  workflow::EditOutcome SetPlan(const std::vector<Vector6d>& poses, bool overwrite = false,
                                const std::vector<Vector6d>* seen = nullptr);

  // legs.csv rows; `legs_error` is why the file does not load, if it does not.
  const std::vector<LegsRow>& Legs() const { return legs_; }
  const QString& LegsError() const { return legs_error_; }
  // One edit of legs.csv as it is on disk: a cell, a holdout, a captured row.
  workflow::EditOutcome EditLegs(const workflow::LegsEdit& edit, bool overwrite = false);
  // A captured frame (a file outside the session) and its readings, added together.
  workflow::EditOutcome RecordCapture(const std::string& frame_file, const LegsRow& row, bool overwrite = false);
  // The same with the image's bytes (a frame the Acquire step encoded).
  workflow::EditOutcome RecordCaptureBytes(const std::string& image_bytes, const LegsRow& row, bool overwrite = false);
  std::vector<QString> ImageFiles() const;  // full paths, sorted

  // Each step's state and the sentence saying why, from
  // workflow::ReadSessionStatus at the last reload: the files' contents.
  StepState State(Step step) const;
  QString Why(Step step) const;
  // Why the Calibrate step is stale or broken ("" when done or to do).
  QString ResultsNote() const;
  // results/ as loaded at the last reload (session/session_results.h), read
  // once per reload for every panel: hashing the images is not free.
  const StatusOr<workflow::SessionResults>& Results() const { return results_; }
  // study/ as loaded at the last reload (session/session_study.h), stale or
  // not by the same input hashes; an error says there is none yet, or why it
  // does not load.
  const StatusOr<workflow::SessionStudy>& Study() const { return study_; }
  // Points the session at another camera file (intrinsics step).
  workflow::EditOutcome SetCamera(const std::string& camera_name, bool overwrite = false);

 signals:
  // Another session folder was opened (before Changed): panels drop what they
  // show of the previous one — images, status texts, running jobs.
  void Switched();
  void Changed();

 private:
  // Reads DIR, which stays open whatever fails to load (the status says what).
  void LoadAll(const QString& dir);
  workflow::EditOutcome ApplyEdit(bool overwrite,
                                  const std::function<workflow::EditOutcome(const workflow::EditOptions&)>& edit);
  void LoadStatus();
  // What the status reads: the folders (whose entries change on a rename, a
  // deletion, a new file) and the files (written in place).
  struct DiskPaths {
    QStringList folders, files;
  };
  DiskPaths Dependencies(const SessionConfig* config) const;
  // Watches exactly `paths` (the watch of a file replaced since is renewed)
  // and records their stamps, before they are read.
  void Watch(const DiskPaths& paths);

  QString dir_;
  SessionConfig config_;
  Robot robot_;
  std::optional<Camera> camera_;
  std::optional<Target> target_;
  std::vector<Vector6d> plan_;
  std::vector<LegsRow> legs_;
  QString legs_error_;
  std::optional<workflow::SessionStatus> status_;  // none when the status could not be read
  StatusOr<workflow::SessionResults> results_ = Status::BadInput("No results yet: run the Calibrate step.");
  StatusOr<workflow::SessionStudy> study_ = Status::BadInput(kNoStudyYet);
  QString load_error_;  // why session.yaml does not load since the last reload; empty when it does
  QFileSystemWatcher watcher_;
  bool watcher_enabled_ = true;
  std::map<QString, std::string> watched_inode_;  // a watched file's inode when its watch began
  std::string stamps_;                            // of every watched path, when last read (ReloadIfChanged)
  QTimer reload_timer_;  // folds a burst of changes (an atomic write is several) into one reload
  QTimer poll_timer_;    // ReloadIfChanged, while the watcher could not take every path (its limit reached)
};

}  // namespace hexcal::ui

// Acquire step: the operator's walk through the planned poses (issue 15), on
// the functions `hexcal acquire` runs (workflow/acquire_step.h).
//
// Left, the plan as a checklist: pose k of N with the x..q3 to command and
// the L1..L6 the nominal robot needs there (Copy puts them on the clipboard),
// each marked recorded (a legs.csv row holds the pose it was commanded to and
// its image is there: by content, not by name, workflow/plan_captures.h),
// skipped, failed or to do. Right, the camera live with the detection overlay
// and readiness indicators: the whole board in view, the reprojection RMS,
// the sharpness. Capture grabs a frame and records it with the readings —
// read from the controller when one is connected, else typed or pasted into
// a dialog prefilled with the commanded lengths — then moves on to the next
// pose; Skip, Redo and (with a controller) Move and Run the rest, disabled
// without one. Typed readings are checked against the stroke and the IK of
// the commanded pose (workflow/reading_check.h). The devices default to the
// sim controller and camera, a pair that connects; another session starts
// from them again. The session is written after every pose
// (workflow::RecordCaptureBytes under the lock).
//
// A points session (docs/session.md, "Points sessions") has no camera: the
// tracker and its own software measure the reflectors. The camera's choice
// and live view give way to what to do at the selected pose — move the robot
// there, record the leg readings (Record readings: from the controller, which
// moves first, or typed), measure the reflectors and export them with the
// pose's name as their group — and each step's state, read from legs.csv and
// the points file (which the window watches: a tracker's export written
// there shows at once). Import points… adds a tracker export to the points
// file; with the sim controller, Sim tracker measures the reflectors where
// the sim platform really is (ui/acquire_points.cc). A pose is recorded when
// it has both.
//
//   auto* acquire = new AcquirePanel(session);
//   acquire->Connect("sim", "sim");  // or linuxcnc://HOST:PORT and aravis:NAME; a worker opens them
//   // ... once Connected() (before, Capture says to connect first):
//   acquire->CapturePose();  // a worker: moves to CurrentPose(), grabs, records it, then selects the next
#pragma once

#include <QWidget>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ui/image_overlay.h"
#include "ui/qt_fwd.h"
#include "ui/session_state.h"

namespace hexcal::workflow {
struct AcquisitionRig;
struct ReadingsRow;
}

namespace hexcal::ui {

class ImageView;

class AcquirePanel : public QWidget {
  Q_OBJECT
 public:
  AcquirePanel(SessionState* session, QWidget* parent = nullptr);
  ~AcquirePanel() override;

  BackgroundJob* Job() const { return job_; }
  QTableWidget* Checklist() const { return checklist_; }
  ImageView* LiveView() const { return live_; }
  int CurrentPose() const { return current_; }  // plan row, from 0; -1 without a plan
  const QString& LastOutcome() const { return outcome_; }
  const OverlayResult& LastFrame() const { return frame_; }
  bool Connected() const { return rig_ != nullptr; }
  // The device URLs as chosen in the combo boxes.
  QString ControllerChoice() const;
  QString CameraChoice() const;
  // The image a capture of plan row `index` has, or would get (workflow/plan_captures.h).
  QString ImageOfPose(int index) const;
  // Points sessions: what to do at the selected pose and each step's state.
  QString PointsGuide() const;

 public slots:
  void Refresh();
  void ResetForSession();
  // "sim", "v4l2:0", "file:PATH"; controller "" or "none" for a robot moved by hand.
  void Connect(const QString& controller_url = {}, const QString& camera_url = {});
  void Disconnect();
  void SelectPose(int index);
  void MoveToPose();
  // Grabs and records the current pose; `typed` readings stand for the
  // dialog (tests, a pasted line) when there is no controller.
  void CapturePose(const std::optional<LegReadings>& typed = std::nullopt);
  void SkipPose();
  void RedoPose();
  void RunRest();
  void GrabLiveFrame();
  // Points sessions: a tracker export (either layout of core/point_file.h)
  // into the points file; a file of one point set is the selected pose's.
  // `chosen` stands for the file dialog (tests).
  void ImportPoints(const QString& chosen = {});
  // Points sessions with the sim controller: the sim tracker's points of the selected pose.
  void MeasureWithSimTracker();

 private:
  void BuildLayout();     // the widgets
  void ArrangeWidgets();  // and where they go
  void FillChecklist();
  // Row `row` of the checklist: its number, `state` and the planned pose.
  void SetChecklistRow(int row, QTableWidgetItem* state, const Vector6d& planned);
  QString PoseState(int index) const;
  // The camera's devices and live view, or a points session's guide (acquire_points.cc).
  void ArrangeForInstrument();
  // A points session's checklist: per pose, its readings and its points.
  void FillPointChecklist(const std::vector<workflow::ReadingsRow>& rows, const std::vector<int>& found);
  void FillPointsGuide();
  // Points sessions: Record readings (from the controller after a move, or typed).
  // `again`: the pose has readings, which the new ones replace (Redo).
  void RecordPointReadings(const std::optional<LegReadings>& typed, bool again);
  // Checked as a controller's (`from_controller`: close to the commanded
  // pose's IK) or as typed ones (workflow/reading_check.h), then saved.
  void SavePointReadings(int index, const LegReadings& readings, bool overwrite, bool from_controller);
  // After readings or points of pose `index` were saved (`done` says which):
  // the line says what the pose still needs, or Refresh has moved on.
  void PointPoseSaved(int index, const QString& done);
  bool PointPoseDone(int index) const;  // readings and points
  void AdvanceWhenRecorded(int index, bool was_done);
  // Selects the next pose to record; false when every pose is recorded or skipped.
  bool NextPose();
  // False (and says why) when the operator's action cannot start now. A live
  // frame in flight is not a reason: `action` then runs when it ends.
  bool ReadyToAct(const QString& what, std::function<void()> action);
  void SetOutcome(const QString& text);
  // Each button enabled when it can act: Capture with devices, Redo with
  // devices on a recorded pose, Move and Run the rest with a controller,
  // Cancel while a step runs.
  void UpdateButtons();
  void ShowFrame(const OverlayResult& frame);
  std::optional<LegReadings> AskReadings(int index);
  void Recorded(int index, const Status& status);
  // The end of Connect's job: the devices, or why not.
  void Connected(std::shared_ptr<workflow::AcquisitionRig> rig, const Status& opened);

  SessionState* session_;
  BackgroundJob* job_;  // every use of the devices, live frames included: one at a time
  std::shared_ptr<workflow::AcquisitionRig> rig_;
  QComboBox *controller_url_, *camera_url_;
  QPushButton *connect_, *move_, *capture_, *skip_, *redo_, *run_rest_, *cancel_, *copy_;
  QCheckBox* live_on_;
  QTimer* live_timer_;
  QLabel *devices_, *pose_label_, *readiness_, *status_;
  QLabel *camera_label_, *guide_;                 // guide_: a points session's steps at the pose
  QPushButton *import_points_, *sim_tracker_;    // points sessions only
  QStackedWidget* right_;                        // the live view, or the points guide
  std::optional<bool> arranged_for_points_;      // the instrument the widgets are arranged for
  std::vector<char> has_points_, has_readings_;  // points sessions, per plan row
  int sim_tracker_draws_ = 0;                    // the sim tracker's noise differs per measurement
  int moved_to_ = -1;  // the plan row the controller last moved to (the sim tracker measures there)
  QProgressBar* progress_;
  QTableWidget* checklist_;
  ImageView* live_;
  OverlayResult frame_;
  std::function<void()> pending_;  // the operator's action waiting for a live frame
  int current_ = -1;
  std::map<int, QString> marks_;  // poses skipped or failed this session: why
  std::vector<std::string> captures_;    // per plan row: its capture's image, "" when none
  std::vector<std::string> free_names_;  // per plan row: the name its next capture gets
  QString outcome_;
  std::vector<Vector6d> outcome_plan_;  // the plan outcome_ is about
  static constexpr const char* kAllDone = "Every planned pose is recorded or skipped: go on to Measure and Calibrate.";
  static constexpr const char* kNoPlan =
      "No plan yet: plan the poses first (Plan step), then come back to record them.";
};

}  // namespace hexcal::ui

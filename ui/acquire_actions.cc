// AcquirePanel's device work: connecting, moving, capturing and the live
// view, each on the panel's one worker (the devices are used by one job at a
// time). The layout and the checklist are in acquire_panel.cc.
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <array>

#include "core/inverse_kinematics.h"
#include "session/readings_table.h"
#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/image_view.h"
#include "ui/quantity_format.h"
#include "ui/text_wrap.h"
#include "vision/image_codecs.h"
#include "workflow/acquire_step.h"
#include "workflow/reading_check.h"
#include "workflow/session_edits.h"

namespace hexcal::ui {
namespace {

constexpr std::chrono::milliseconds kGrabTimeout{2000};
constexpr const char* kLiveJob = "live";  // the live view's frames, which an operator's action may wait for
constexpr uint64_t kSimSeed = 1;  // the sim world's truth: the same every time, so a session resumes

QString Message(const Status& status) { return QString::fromStdString(status.message()); }

bool ByHand(const QString& controller) { return controller.isEmpty() || controller.startsWith("none"); }

}  // namespace

// Opening the devices can take long (a LinuxCNC machine powers on and homes,
// up to its motion time-out): it runs as a job, and the window stays live.
void AcquirePanel::Connect(const QString& controller_url, const QString& camera_url) {
  if (!session_->IsOpen()) return ShowError(this, "Connect", "Open or create a session first (File menu).");
  if (!controller_url.isEmpty()) controller_url_->setCurrentText(controller_url);
  if (!camera_url.isEmpty()) camera_url_->setCurrentText(camera_url);
  if (job_->Running()) {
    if (job_->What() != kLiveJob && !job_->Abandoned())
      return ShowError(this, "Connect", "The devices are busy: wait for the current step, or press Cancel.");
    pending_ = [this] { Connect({}, {}); };  // after the live frame (or dropped job) in flight
    return;
  }
  const std::string controller = ControllerChoice().toStdString();
  // A points session's tracker is not a device of hexcal's: no camera.
  const std::string camera = session_->IsPointsSession() ? std::string() : CameraChoice().toStdString();
  const std::string dir = session_->Dir().toStdString();
  const bool by_hand = ByHand(QString::fromStdString(controller));
  // Said here in the panel's terms (the workflow's message names the CLI's flag).
  if (camera == "sim" && controller != "sim")
    return ShowError(this, "Connect",
                     "The sim camera shows the sim controller's platform: choose 'sim' in the Controller list too, "
                     "or another camera (aravis:NAME, v4l2:N, file:PATH).");
  Disconnect();
  devices_->setText("Connecting (a machine may power on and home first)…");
  job_->Start("connecting", [this, controller, camera, dir, by_hand](const JobContext&) -> GuiContinuation {
    auto rig = std::make_shared<workflow::AcquisitionRig>();
    Status opened = Status::Ok();
    if (by_hand && camera.empty()) {
      // A points session by hand: nothing to open; the readings are typed.
    } else if (by_hand) {
      StatusOr<std::unique_ptr<workflow::FrameSource>> source = workflow::OpenFrameSource(camera);
      if (source.ok()) rig->camera = std::move(*source);
      opened = source.status();
    } else {
      StatusOr<workflow::AcquisitionRig> both = workflow::OpenAcquisitionRig(dir, controller, camera, kSimSeed);
      if (both.ok()) *rig = std::move(*both);
      opened = both.status();
    }
    return [this, rig, opened] { Connected(rig, opened); };
  });
}

void AcquirePanel::Connected(std::shared_ptr<workflow::AcquisitionRig> rig, const Status& opened) {
  if (!opened.ok()) {
    devices_->setText("Not connected.");
    return ShowError(this, "Connect", Message(opened));
  }
  rig_ = std::move(rig);
  const QString controller = rig_->controller ? QString::fromStdString(rig_->controller->Describe())
                                              : "no controller (move the robot by hand, type the readings)";
  // A points session's rig has no camera; with the sim controller, the sim tracker beside it.
  const QString second = rig_->camera ? QString::fromStdString(rig_->camera->Describe())  // a file: camera's path
                         : rig_->sim  ? "the sim tracker (its reflectors where the sim platform really is)"
                                      : "the tracker's points come from its software (the points file, Import points…)";
  devices_->setText(Breakable(QString("Connected: %1; %2.").arg(controller, second)));
  connect_->setText("Disconnect");
  UpdateButtons();
  GrabLiveFrame();
}

void AcquirePanel::Disconnect() {
  pending_ = nullptr;
  moved_to_ = -1;
  rig_.reset();  // a running job keeps its own reference until it ends
  connect_->setText("Connect");
  devices_->setText("Not connected.");
  live_->SetMessage("Connect a camera to see it live.");
  readiness_->setText("No camera connected.");
  frame_ = OverlayResult{};
  UpdateButtons();
}

bool AcquirePanel::ReadyToAct(const QString& what, std::function<void()> action) {
  if (!session_->IsOpen()) return ShowError(this, what, "Open or create a session first (File menu)."), false;
  if (!rig_)
    return ShowError(this, what,
                     session_->IsPointsSession() ? "Connect a controller first (Controller, Connect)."
                                                 : "Connect a camera first (and a controller, or move by hand)."),
           false;
  if (current_ < 0) return ShowError(this, what, "There is no planned pose: plan first (Plan step)."), false;
  if (job_->Running() && !job_->Abandoned() && job_->What() == kLiveJob) {
    // A live frame in flight ends in a moment (the camera's time-out at most): then the action.
    pending_ = std::move(action);
    return false;
  }
  if (job_->Running() && !job_->Abandoned())
    return ShowError(this, what, "The devices are busy: wait for the current step, or press Cancel."), false;
  return true;
}

void AcquirePanel::MoveToPose() {
  if (!ReadyToAct("Move", [this] { MoveToPose(); })) return;
  if (!rig_->controller)
    return ShowError(this, "Move", "No controller connected: move the robot by hand to the lengths shown.");
  const Vector6d pose = session_->Plan()[current_];
  const int index = current_;
  SetOutcome(QString("moving to pose %1…").arg(index + 1));
  job_->Start("moving", [this, rig = rig_, pose, index](const JobContext&) -> GuiContinuation {
    Status moved = rig->controller->MoveTo(pose);
    if (moved.ok()) moved = rig->controller->WaitSettled(0);
    return [this, moved, index] {
      if (!moved.ok()) return SetOutcome(QString("pose %1: %2").arg(index + 1).arg(Message(moved)));
      moved_to_ = index;
      SetOutcome(session_->IsPointsSession()
                     ? QString("at pose %1: Record readings, and measure the reflectors with the tracker.").arg(index + 1)
                     : QString("at pose %1: check the live view, then Capture.").arg(index + 1));
      GrabLiveFrame();
    };
  });
}

void AcquirePanel::CapturePose(const std::optional<LegReadings>& typed) {
  if (session_->IsPointsSession()) return RecordPointReadings(typed, /*again=*/false);
  if (!ReadyToAct("Capture", [this, typed] { CapturePose(typed); })) return;
  const int index = current_;
  const Vector6d pose = session_->Plan()[index];
  const std::string dir = session_->Dir().toStdString();
  SetOutcome(QString("capturing pose %1…").arg(index + 1));
  if (rig_->controller) {
    // The controller's whole step: move, settle, grab, read the legs, record.
    job_->Start("capturing", [this, rig = rig_, dir, pose, index](const JobContext& context) -> GuiContinuation {
      StatusOr<workflow::PoseRecord> record =
          workflow::AcquirePose(dir, index, pose, *rig->controller, *rig->camera, {}, context);
      const Status status = record.ok() ? Status::Ok() : record.status();
      return [this, status, index] { Recorded(index, status); };
    });
    return;
  }
  const Camera camera = *session_->SessionCamera();
  const Target target = *session_->SessionTarget();
  const std::string image = ImageOfPose(index).toStdString();
  job_->Start(
      "grabbing", [this, rig = rig_, camera, target, index, typed, pose, image](const JobContext&) -> GuiContinuation {
        StatusOr<cv::Mat> frame = rig->camera->Grab(kGrabTimeout);
        StatusOr<std::string> png = frame.ok() ? EncodePng(*frame) : StatusOr<std::string>(frame.status());
        if (!png.ok()) frame = png.status();
        const OverlayResult overlay = frame.ok() ? DetectAndDraw(*frame, camera, target) : OverlayResult{};
        const std::string bytes = png.ok() ? *png : std::string();
        const Status grabbed = frame.ok() ? Status::Ok() : frame.status();
        return [this, grabbed, overlay, bytes, index, typed, pose, image] {
          if (!grabbed.ok()) return Recorded(index, grabbed);
          ShowFrame(overlay);
          const std::optional<LegReadings> readings = typed ? typed : AskReadings(index);
          if (!readings) return SetOutcome("not recorded: no readings entered.");
          // Against the stroke and the commanded pose's IK lengths (reading_check.h).
          const Status plausible = workflow::CheckTypedReadings(
              workflow::MakeReadingCheck(session_->NominalRobot(), session_->Config().noise), image, *readings, pose);
          if (!plausible.ok()) {
            SetOutcome("not recorded: " + Message(plausible));
            return ShowError(this, "Capture", Message(plausible) + "\nCapture again and check the readings.");
          }
          LegsRow row;
          row.image = image;
          row.legs = *readings;
          row.commanded = pose;  // ties the image to this planned pose (workflow/plan_captures.h)
          const bool saved = ApplySessionEdit(
              this, "Capture", [&](bool overwrite) { return session_->RecordCaptureBytes(bytes, row, overwrite); });
          Recorded(index, saved ? Status::Ok() : Status::Failed("not saved"));
        };
      });
}

// After the capture of pose `index` (the one the job was started for, even if
// the operator has picked another since): the checklist, the next pose, or
// the failure marked.
void AcquirePanel::Recorded(int index, const Status& status) {
  if (status.cancelled()) return SetOutcome("cancelled: nothing recorded for this pose.");
  if (!status.ok()) {
    marks_[index] = "failed: " + Message(status);
    FillChecklist();
    SetOutcome(QString("pose %1 failed: %2").arg(index + 1).arg(Message(status)));
    return;
  }
  FillChecklist();
  const QString image = ImageOfPose(index);
  const bool more = NextPose();
  SetOutcome(QString("pose %1 recorded as %2 (saved to the session).%3")
                 .arg(index + 1)
                 .arg(image, more ? QString() : QString(" ") + kAllDone));
}

// The readings at the pose, prefilled with the lengths the nominal robot
// needs there: the operator types the sensors' values or pastes a line.
std::optional<LegReadings> AcquirePanel::AskReadings(int index) {
  const Robot& robot = session_->NominalRobot();
  const LegReadings planned = InverseKinematics(robot, robot.PoseFromVector(session_->Plan()[index]));
  if (!Interactive()) return planned;
  QDialog dialog(this);
  dialog.setWindowTitle(QString("Leg readings at pose %1").arg(index + 1));
  auto* form = new QFormLayout(&dialog);
  auto* paste = new QLineEdit;
  paste->setPlaceholderText("paste six readings (tabs, commas or spaces)");
  form->addRow("Paste", paste);
  std::array<QDoubleSpinBox*, kNumLegs> boxes;
  for (int i = 0; i < kNumLegs; ++i) {
    boxes[i] = new QDoubleSpinBox;
    boxes[i]->setRange(-1e6, 1e6);
    boxes[i]->setDecimals(5);
    boxes[i]->setValue(planned[i]);
    form->addRow(QString("L%1 (%2)").arg(i + 1).arg(LengthUnitName(robot.length_unit)), boxes[i]);
  }
  connect(paste, &QLineEdit::textChanged, &dialog, [&](const QString& text) {
    if (const auto legs = workflow::ParseReadingsLine(text.toStdString()))
      for (int i = 0; i < kNumLegs; ++i) boxes[i]->setValue((*legs)[i]);
  });
  auto* ok = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  form->addRow(ok);
  connect(ok, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  connect(ok, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  if (dialog.exec() != QDialog::Accepted) return std::nullopt;
  LegReadings legs;
  for (int i = 0; i < kNumLegs; ++i) legs[i] = boxes[i]->value();
  return legs;
}

void AcquirePanel::RedoPose() {
  if (session_->IsPointsSession()) {
    if (current_ < 0 || current_ >= static_cast<int>(captures_.size()) || captures_[current_].empty()) return;
    if (Interactive() &&
        QMessageBox::question(this, "Redo pose", QString("Record the readings of pose %1 (%2) again, replacing "
                                                         "those in legs.csv?")
                                                     .arg(current_ + 1)
                                                     .arg(ImageOfPose(current_))) != QMessageBox::Yes)
      return;
    return RecordPointReadings(std::nullopt, /*again=*/true);
  }
  if (!ReadyToAct("Redo", [this] { RedoPose(); })) return;
  if (current_ >= static_cast<int>(captures_.size()) || captures_[current_].empty()) return CapturePose();
  const std::string image = captures_[current_];  // the capture of this pose, whatever its name
  if (Interactive() &&
      QMessageBox::question(this, "Redo pose", QString("Remove %1 and its readings, and capture pose %2 again?")
                                                   .arg(QString::fromStdString(image))
                                                   .arg(current_ + 1)) != QMessageBox::Yes)
    return;
  const Status removed = workflow::RemoveCapture(session_->Dir().toStdString(), image);
  if (!removed.ok()) return ShowError(this, "Redo", Message(removed));
  marks_.erase(current_);
  session_->Reload();
  CapturePose();
}

void AcquirePanel::RunRest() {
  // The tracker measures each pose before the robot leaves it: one pose at a time.
  if (session_->IsPointsSession())
    return ShowError(this, "Run the rest", "A points session records one pose at a time: Record readings, then the "
                                           "tracker's points, then the next pose.");
  if (!ReadyToAct("Run the rest", [this] { RunRest(); })) return;
  if (!rig_->controller)
    return ShowError(this, "Run the rest", "Needs a controller: choose one in the Controller list and Connect.");
  workflow::AcquireRequest request;
  request.session = session_->Dir().toStdString();
  SetOutcome("acquiring the poses not yet recorded…");
  job_->Start("acquiring", [this, rig = rig_, request](const JobContext& context) -> GuiContinuation {
    StatusOr<workflow::AcquireResult> run = workflow::AcquirePlan(request, *rig->controller, *rig->camera, context);
    const Status status = run.ok() ? Status::Ok() : run.status();
    const QString summary = run.ok() ? QString::fromStdString(workflow::FormatAcquireSummary(*run)) : QString();
    return [this, status, summary] {
      session_->Reload();
      if (status.cancelled()) return SetOutcome("stopped: the poses recorded so far are saved; Run the rest resumes.");
      if (!status.ok()) return ShowError(this, "Run the rest", Message(status));
      SetOutcome(summary.trimmed());
    };
  });
}

void AcquirePanel::GrabLiveFrame() {
  if (!rig_ || job_->Running() || !session_->SessionCamera() || !session_->SessionTarget()) return;
  const Camera camera = *session_->SessionCamera();
  const Target target = *session_->SessionTarget();
  job_->Start(kLiveJob, [this, rig = rig_, camera, target](const JobContext&) -> GuiContinuation {
    StatusOr<cv::Mat> frame = rig->camera->Grab(kGrabTimeout);
    // A frame of devices disconnected meanwhile is not shown: "Not connected"
    // beside the last frame and its "ready" would be a text outliving its job.
    if (!frame.ok())
      return [this, rig, s = frame.status()] {
        if (rig_ == rig) readiness_->setText("No frame: " + Message(s).toHtmlEscaped());
      };
    const OverlayResult overlay = DetectAndDraw(*frame, camera, target);
    return [this, rig, overlay] {
      if (rig_ == rig) ShowFrame(overlay);
    };
  });
}

// The frame and its readiness: each indicator green when it passes.
void AcquirePanel::ShowFrame(const OverlayResult& frame) {
  frame_ = frame;
  if (!frame.image.isNull()) live_->SetImage(frame.image);
  const auto mark = [](bool good, const QString& text) {
    return QString("<span style='color:%1'>%2 %3</span>").arg(good ? "#007800" : "#be0000", good ? "✓" : "✗", text);
  };
  const QString problem = ReadinessProblem(frame);
  readiness_->setText(
      mark(frame.whole_board_in_view, QString("board %1/%2 tags, whole in view").arg(frame.tags).arg(frame.board_tags)) +
      " &nbsp; " + mark(frame.ok && frame.rms_px <= kReadyMaxRmsPx, "RMS " + FormatPixels(frame.rms_px)) + " &nbsp; " +
      mark(frame.sharpness >= kReadyMinSharpness, QString("sharpness %1").arg(frame.sharpness, 0, 'f', 0)) +
      (problem.isEmpty() ? " &nbsp; <b>ready</b>" : " &nbsp; " + problem.toHtmlEscaped()));
}

}  // namespace hexcal::ui

#include "ui/acquire_panel.h"

#include <QApplication>
#include <QCheckBox>
#include <QClipboard>
#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QSplitter>
#include <QStackedWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <array>
#include <set>

#include "core/inverse_kinematics.h"
#include "session/readings_table.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/image_view.h"
#include "ui/quantity_format.h"
#include "ui/table_cell.h"
#include "ui/text_wrap.h"
#include "workflow/acquire_step.h"
#include "workflow/plan_captures.h"
#include "workflow/reading_check.h"

namespace hexcal::ui {
namespace {

constexpr int kLiveIntervalMs = 600;
// The devices a session starts with: the sim controller and its camera, a
// pair that connects (the sim camera renders the sim controller's platform).
constexpr int kDefaultController = 1;  // "sim"
constexpr int kDefaultCamera = 0;      // "sim"
const QString kPlanBroken = "The plan does not load: ";
const QString kPlanAgain = " Fix plan.csv, or plan again (Plan step).";

QString Joined(const Vector6d& v, int from, int count) {
  QStringList parts;
  for (int k = from; k < from + count; ++k) parts << FormatCoordinate(v[k]);
  return parts.join("  ");
}

}  // namespace

AcquirePanel::AcquirePanel(SessionState* session, QWidget* parent)
    : QWidget(parent), session_(session), job_(new BackgroundJob(this)), live_timer_(new QTimer(this)) {
  BuildLayout();
  ShowProgressOn(job_, progress_);
  live_timer_->setInterval(kLiveIntervalMs);
  connect(live_timer_, &QTimer::timeout, this, [this] {
    if (isVisible() && live_on_->isChecked()) GrabLiveFrame();
  });
  live_timer_->start();
  // An action pressed while a live frame was in flight (ReadyToAct) runs now.
  connect(job_, &BackgroundJob::Finished, this, [this] {
    if (!pending_ || job_->Running()) return;
    std::function<void()> action = std::move(pending_);
    pending_ = nullptr;
    action();
  });
  connect(job_, &BackgroundJob::Started, this, &AcquirePanel::UpdateButtons);
  connect(job_, &BackgroundJob::Finished, this, &AcquirePanel::UpdateButtons);
  connect(session_, &SessionState::Switched, this, &AcquirePanel::ResetForSession);
  connect(session_, &SessionState::Changed, this, &AcquirePanel::Refresh);
  UpdateButtons();
}

AcquirePanel::~AcquirePanel() = default;

void AcquirePanel::BuildLayout() {
  controller_url_ = new QComboBox;
  controller_url_->setObjectName("acquire_controller");
  controller_url_->setEditable(true);
  controller_url_->addItems({"none (move the robot by hand)", "sim", "linuxcnc://localhost:5007"});
  controller_url_->setCurrentIndex(kDefaultController);
  controller_url_->setToolTip("The controller that moves the robot and reads its legs (docs/acquisition.md)");
  camera_url_ = new QComboBox;
  camera_url_->setObjectName("acquire_camera");
  camera_url_->setEditable(true);
  camera_url_->addItems({"sim", "aravis:", "v4l2:0", "file:"});
  camera_url_->setCurrentIndex(kDefaultCamera);
  camera_url_->setToolTip(
      "The camera: sim, aravis:NAME (GenICam through Aravis), v4l2:N (OpenCV), file:PATH (a video or an image)");
  connect_ = new QPushButton("Connect");
  connect_->setObjectName("acquire_connect");
  connect(connect_, &QPushButton::clicked, this, [this] { Connected() ? Disconnect() : Connect(); });
  devices_ = new QLabel("Not connected.");
  devices_->setWordWrap(true);
  devices_->setTextFormat(Qt::PlainText);
  checklist_ = new QTableWidget(0, 4);
  checklist_->setObjectName("pose_checklist");
  checklist_->setHorizontalHeaderLabels({"#", "state", "x  y  z", "q1  q2  q3 (°)"});
  checklist_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  checklist_->horizontalHeader()->setStretchLastSection(true);
  checklist_->setSelectionBehavior(QAbstractItemView::SelectRows);
  checklist_->verticalHeader()->setVisible(false);  // the # column numbers the poses
  checklist_->setSelectionMode(QAbstractItemView::SingleSelection);
  connect(checklist_, &QTableWidget::currentCellChanged, this, [this](int row) { SelectPose(row); });
  pose_label_ = new QLabel;
  pose_label_->setObjectName("acquire_pose");
  pose_label_->setTextFormat(Qt::PlainText);
  pose_label_->setWordWrap(true);  // a label's one line is its minimum width
  pose_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  copy_ = new QPushButton("Copy");
  copy_->setToolTip("Put the pose (x y z q1 q2 q3) and the leg lengths to command on the clipboard");
  connect(copy_, &QPushButton::clicked, this, [this] { QApplication::clipboard()->setText(pose_label_->text()); });
  const auto button = [this](const QString& text, const QString& tip, auto slot) {
    auto* made = new QPushButton(text);
    made->setObjectName("acquire_" + text.toLower().replace(' ', '_'));  // "acquire_run_the_rest"
    made->setToolTip(tip);
    connect(made, &QPushButton::clicked, this, slot);
    return made;
  };
  move_ = button("Move", "Command the controller to this pose and wait until it settles (needs a controller)",
                 [this] { MoveToPose(); });
  capture_ = button("Capture", "Grab a frame and record it with the leg readings, then go to the next pose",
                    [this] { CapturePose(); });
  skip_ = button("Skip", "Leave this pose for later and go to the next", [this] { SkipPose(); });
  redo_ = button("Redo", "Remove this pose's image and readings and capture it again", [this] { RedoPose(); });
  run_rest_ = button("Run the rest", "Move, capture and record every pose not yet recorded (needs a controller)",
                     [this] { RunRest(); });
  cancel_ = button("Cancel", "Stop after the current pose", [this] { job_->Cancel(); });
  live_on_ = new QCheckBox("Live view");
  live_on_->setChecked(true);
  progress_ = new QProgressBar;
  status_ = new QLabel;
  status_->setObjectName("acquire_status");
  status_->setWordWrap(true);
  status_->setTextFormat(Qt::PlainText);
  readiness_ = new QLabel("No camera connected.");
  readiness_->setObjectName("acquire_readiness");
  readiness_->setTextFormat(Qt::RichText);
  readiness_->setWordWrap(true);
  live_ = new ImageView;
  live_->setObjectName("live_view");
  live_->SetMessage("Connect a camera to see it live.");
  camera_label_ = new QLabel("Camera");
  guide_ = new QLabel;
  guide_->setObjectName("acquire_points_guide");
  guide_->setTextFormat(Qt::RichText);
  guide_->setWordWrap(true);
  guide_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  guide_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  import_points_ = button("Import points", "Add a tracker export (SpatialAnalyzer ASCII or CSV) to the session's "
                          "points file; a file of one point set is the selected pose's", [this] { ImportPoints(); });
  import_points_->setText("Import points…");
  sim_tracker_ = button("Sim tracker", "Measure the reflectors with the simulated tracker where the sim platform is "
                        "now, and add them to the points file as the selected pose's", [this] { MeasureWithSimTracker(); });
  ArrangeWidgets();
}

void AcquirePanel::ArrangeWidgets() {
  // Two rows of devices and of actions: one row of each was wider than a
  // 1280 px window's panel.
  for (QComboBox* url : {controller_url_, camera_url_}) {
    url->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    url->setMinimumContentsLength(12);
  }
  auto* devices = new QGridLayout;
  devices->addWidget(new QLabel("Controller"), 0, 0);
  devices->addWidget(controller_url_, 0, 1);
  devices->addWidget(camera_label_, 1, 0);
  devices->addWidget(camera_url_, 1, 1);
  devices->addWidget(connect_, 0, 2, 2, 1);
  devices->setColumnStretch(1, 1);
  auto* pose_row = new QHBoxLayout;
  pose_row->addWidget(pose_label_, 1);
  pose_row->addWidget(copy_);
  auto* actions = new QGridLayout;
  const std::array<QPushButton*, 6> buttons{capture_, skip_, redo_, move_, run_rest_, cancel_};
  for (int k = 0; k < static_cast<int>(buttons.size()); ++k) actions->addWidget(buttons[k], k / 3, k % 3);
  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  left_layout->addLayout(devices);
  left_layout->addWidget(devices_);
  left_layout->addWidget(checklist_, 1);
  left_layout->addLayout(pose_row);
  left_layout->addLayout(actions);
  left_layout->addWidget(progress_);
  left_layout->addWidget(status_);
  auto* camera_page = new QWidget;
  auto* right_layout = new QVBoxLayout(camera_page);
  right_layout->addWidget(live_, 1);
  auto* live_row = new QHBoxLayout;
  live_row->addWidget(live_on_);
  live_row->addWidget(readiness_, 1);
  right_layout->addLayout(live_row);
  auto* points_page = new QWidget;
  auto* points_layout = new QVBoxLayout(points_page);
  // The guide scrolls on its own: at 1024×600 its steps are taller than the
  // panel, and the buttons below it must stay in view.
  auto* guide_scroll = new QScrollArea;
  guide_scroll->setObjectName("acquire_points_guide_scroll");
  guide_scroll->setWidgetResizable(true);
  guide_scroll->setFrameShape(QFrame::NoFrame);
  guide_scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  // Wrapped to the scroll area's width, not widened past it by its longest word.
  guide_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  guide_scroll->setWidget(guide_);
  points_layout->addWidget(guide_scroll, 1);
  auto* points_buttons = new QHBoxLayout;
  points_buttons->addWidget(import_points_);
  points_buttons->addWidget(sim_tracker_);
  points_buttons->addStretch();
  points_layout->addLayout(points_buttons);
  right_ = new QStackedWidget;
  right_->addWidget(camera_page);
  right_->addWidget(points_page);
  auto* splitter = new QSplitter;
  splitter->addWidget(left);
  splitter->addWidget(right_);
  splitter->setStretchFactor(1, 1);
  splitter->setSizes({560, 520});
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(splitter);
}

QString AcquirePanel::PoseState(int index) const {
  const auto mark = marks_.find(index);
  if (mark != marks_.end()) return mark->second;
  return "to do";
}

QString AcquirePanel::ControllerChoice() const { return controller_url_->currentText().trimmed(); }
QString AcquirePanel::CameraChoice() const { return camera_url_->currentText().trimmed(); }

QString AcquirePanel::ImageOfPose(int index) const {
  if (index < 0) return {};
  if (index < static_cast<int>(captures_.size()) && !captures_[index].empty())
    return QString::fromStdString(captures_[index]);
  if (index < static_cast<int>(free_names_.size())) return QString::fromStdString(free_names_[index]);
  return QString::fromStdString(workflow::AcquiredImageName(index));
}

// A pose is recorded when a legs.csv row holds the pose it was commanded to
// and its image is there: by content, so an image of an earlier plan that
// happens to have the name of this plan's pose does not count
// (workflow/plan_captures.h).
void AcquirePanel::FillChecklist() {
  StatusOr<std::vector<workflow::ReadingsRow>> rows =
      session_->IsOpen() ? workflow::ReadReadingsTable(session_->Dir().toStdString())
                         : StatusOr<std::vector<workflow::ReadingsRow>>(std::vector<workflow::ReadingsRow>{});
  const std::vector<workflow::ReadingsRow> shown = rows.ok() ? *rows : std::vector<workflow::ReadingsRow>{};
  const std::vector<Vector6d>& plan = session_->Plan();
  const std::vector<int> found = workflow::CapturesOfPlan(
      workflow::MakeReadingCheck(session_->NominalRobot(), session_->Config().noise), plan, shown);
  captures_.assign(plan.size(), std::string());
  free_names_.clear();
  checklist_->horizontalHeaderItem(2)->setText(
      QString("x  y  z (%1)").arg(LengthUnitName(session_->NominalRobot().length_unit)));
  if (session_->IsPointsSession()) return FillPointChecklist(shown, found);
  checklist_->blockSignals(true);
  checklist_->setRowCount(static_cast<int>(plan.size()));
  for (int k = 0; k < static_cast<int>(plan.size()); ++k) {
    const bool done = found[k] >= 0 && shown[found[k]].image_present;
    if (done) captures_[k] = shown[found[k]].image;
    free_names_.push_back(workflow::CaptureImageName(k, shown));
    if (done) marks_.erase(k);
    const QString state = done ? "✓ recorded" : PoseState(k);
    QTableWidgetItem* state_cell = TableCell(state);
    if (done) state_cell->setToolTip(QString::fromStdString(captures_[k]));
    state_cell->setForeground(done ? QColor(0, 120, 0) : state.startsWith("failed") ? QColor(190, 0, 0)
                                                                                    : QColor(90, 90, 90));
    SetChecklistRow(k, state_cell, plan[k]);
  }
  checklist_->blockSignals(false);
}

void AcquirePanel::SetChecklistRow(int row, QTableWidgetItem* state, const Vector6d& planned) {
  checklist_->setItem(row, 0, TableCell(QString::number(row + 1)));
  checklist_->setItem(row, 1, state);
  checklist_->setItem(row, 2, TableCell(Joined(planned, 0, 3)));
  checklist_->setItem(row, 3, TableCell(Joined(planned, 3, 3)));
}

void AcquirePanel::Refresh() {
  ArrangeForInstrument();
  const int shown = current_;
  const bool shown_done = PointPoseDone(shown);
  // A line about another plan ("12 recorded, of 12 poses") does not outlive it.
  if (!job_->Running() && !outcome_.isEmpty() && session_->Plan() != outcome_plan_) SetOutcome({});
  FillChecklist();
  const int poses = checklist_->rowCount();
  if (current_ < 0 || current_ >= poses) {
    current_ = -1;
    if (!NextPose() && poses > 0) SetOutcome(kAllDone);
  } else {
    SelectPose(current_);
  }
  // The plan line from the status (issue 40): no plan, or one that does not
  // load; gone as soon as a plan is listed.
  if (poses == 0) {
    current_ = -1;
    pose_label_->setText("no pose");
    SetOutcome(session_->State(Step::kPlan) == StepState::kBroken
                   ? kPlanBroken + session_->InSession(session_->Why(Step::kPlan)) + kPlanAgain
                   : QString(kNoPlan));
    UpdateButtons();
  } else if (outcome_ == kNoPlan || outcome_.startsWith(kPlanBroken)) {
    SetOutcome({});  // a plan came: the line would send the operator back for nothing
  }
  AdvanceWhenRecorded(shown, shown_done);
}

// Nothing of the last session stays: its devices, pose, lengths, marks and
// texts; the device choice is the default pair again.
void AcquirePanel::ResetForSession() {
  job_->Abandon();
  Disconnect();
  marks_.clear();
  captures_.clear();
  free_names_.clear();
  current_ = -1;
  controller_url_->setCurrentIndex(kDefaultController);
  camera_url_->setCurrentIndex(kDefaultCamera);
  pose_label_->setText("no pose");
  checklist_->setRowCount(0);
  progress_->reset();
  SetOutcome({});
  UpdateButtons();
}

void AcquirePanel::UpdateButtons() {
  const bool busy = job_->Running() && !job_->Abandoned() && job_->What() != "live";
  const bool pose = current_ >= 0;
  const bool controller = rig_ && rig_->controller;
  const bool points = session_->IsPointsSession();
  // A points session's readings may be typed without connecting: there is no camera to open.
  capture_->setEnabled((rig_ || points) && pose);
  const bool recorded = pose && current_ < static_cast<int>(captures_.size()) && !captures_[current_].empty();
  redo_->setEnabled((rig_ || points) && recorded);  // a pose not recorded is captured, not redone
  import_points_->setEnabled(pose && !busy);
  sim_tracker_->setVisible(points && rig_ && rig_->sim);
  sim_tracker_->setEnabled(pose && !busy);
  run_rest_->setVisible(!points);  // the tracker measures each pose before the robot moves on
  skip_->setEnabled(pose);
  copy_->setEnabled(pose);
  move_->setEnabled(controller && pose);
  run_rest_->setEnabled(controller && pose);
  cancel_->setEnabled(busy);
  const QString why = !rig_ && points ? "Connect a controller first (Controller, Connect)."
                    : !rig_          ? "Connect the devices first (Controller, Camera, Connect)."
                            : QString("No controller connected: choose one (Controller) and Connect; by hand, move "
                                      "the robot to the lengths shown and press %1.")
                                  .arg(points ? "Record readings" : "Capture");
  // A tooltip's first line is the button's; a second, while it is disabled, says why.
  for (QPushButton* needs : {move_, run_rest_})
    needs->setToolTip(needs->isEnabled() ? needs->toolTip().section("\n", 0, 0)
                                         : needs->toolTip().section("\n", 0, 0) + "\n" + why);
}

void AcquirePanel::SelectPose(int index) {
  const std::vector<Vector6d>& plan = session_->Plan();
  if (index < 0 || index >= static_cast<int>(plan.size())) {
    pose_label_->setText("no pose");
    return UpdateButtons();
  }
  current_ = index;
  if (checklist_->currentRow() != index) {
    checklist_->blockSignals(true);
    checklist_->selectRow(index);
    checklist_->blockSignals(false);
  }
  const Robot& robot = session_->NominalRobot();
  const LegReadings legs = InverseKinematics(robot, robot.PoseFromVector(plan[index]));
  QStringList lengths;
  for (int i = 0; i < kNumLegs; ++i) lengths << FormatCoordinate(legs[i]);
  pose_label_->setText(QString("pose %1 of %2 (%3): x y z = %4 %7, q1 q2 q3 = %5°\nL1..L6 = %6 %7")
                           .arg(index + 1)
                           .arg(plan.size())
                           .arg(ImageOfPose(index))
                           .arg(Joined(plan[index], 0, 3), Joined(plan[index], 3, 3), lengths.join("  "),
                                LengthUnitName(robot.length_unit)));
  FillPointsGuide();
  UpdateButtons();
}

// The next pose after the current one that is neither recorded nor skipped.
bool AcquirePanel::NextPose() {
  const int poses = checklist_->rowCount();
  for (int step = 1; step <= poses; ++step) {
    const int k = (current_ + step + poses) % poses;
    const QString state = checklist_->item(k, 1)->text();
    // Not recorded, not skipped: to do, failed, or (points) half recorded.
    if (!state.startsWith("✓") && state != "skipped") {
      SelectPose(k);
      return true;
    }
  }
  if (poses > 0) SelectPose(std::max(current_, 0));
  return false;
}

void AcquirePanel::SkipPose() {
  if (current_ < 0) return;
  marks_[current_] = "skipped";
  FillChecklist();
  if (!NextPose()) SetOutcome(kAllDone);
}

void AcquirePanel::SetOutcome(const QString& text) {
  outcome_ = InGuiTerms(text);  // the workflow's errors name the CLI's flags
  outcome_plan_ = session_->Plan();
  status_->setText(Breakable(outcome_));  // it may quote a long path
}

}  // namespace hexcal::ui

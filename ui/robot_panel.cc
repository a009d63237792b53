#include "ui/robot_panel.h"

#include <QCheckBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QSlider>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/candidates.h"
#include "ui/quantity_format.h"
#include "ui/robot_view.h"

namespace hexcal::ui {
namespace {

constexpr int kWorkspaceSamples = 400;

QString Vec(const Eigen::Vector3d& v) {
  return QString("%1  %2  %3").arg(FormatCoordinate(v.x()), FormatCoordinate(v.y()), FormatCoordinate(v.z()));
}

}  // namespace

RobotPanel::RobotPanel(SessionState* session, QWidget* parent)
    : QWidget(parent), session_(session), view_(new RobotView) {
  summary_ = new QLabel;
  summary_->setTextFormat(Qt::RichText);  // names from files are escaped where they are set
  summary_->setWordWrap(true);
  summary_->setObjectName("robot_summary");
  legs_ = new QTableWidget(kNumLegs, 4);
  legs_->setObjectName("robot_legs");
  legs_->setHorizontalHeaderLabels({"a (base)", "b (platform)", "offset l", "stroke"});
  legs_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  legs_->setEditTriggers(QAbstractItemView::NoEditTriggers);

  scrub_ = new QSlider(Qt::Horizontal);
  scrub_->setObjectName("pose_scrub");
  scrub_->setToolTip("Scrub through the planned poses");
  scrub_label_ = new QLabel;
  scrub_label_->setTextFormat(Qt::PlainText);  // file names are shown as they are, never as HTML
  scrub_label_->setWordWrap(true);
  ghosts_ = new QCheckBox("Planned poses as ghosts");
  ghosts_->setChecked(true);
  samples_ = new QCheckBox(QString("Workspace samples (%1 random feasible poses)").arg(kWorkspaceSamples));
  camera_ = new QCheckBox("Camera frustum and target (once registered)");
  camera_->setChecked(true);
  connect(scrub_, &QSlider::valueChanged, this, &RobotPanel::ShowPlannedPose);
  for (QCheckBox* box : {ghosts_, samples_, camera_})
    connect(box, &QCheckBox::toggled, this, &RobotPanel::UpdateOverlays);

  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  left_layout->addWidget(summary_);
  left_layout->addWidget(legs_, 1);
  left_layout->addWidget(ghosts_);
  left_layout->addWidget(samples_);
  left_layout->addWidget(camera_);
  auto* right = new QWidget;
  auto* right_layout = new QVBoxLayout(right);
  right_layout->addWidget(view_, 1);
  auto* scrub_row = new QHBoxLayout;
  scrub_row->addWidget(scrub_label_);
  scrub_row->addWidget(scrub_, 1);
  right_layout->addLayout(scrub_row);
  auto* splitter = new QSplitter;
  splitter->addWidget(left);
  splitter->addWidget(right);
  splitter->setStretchFactor(1, 2);
  splitter->setSizes({600, 780});  // the legs' table whole at 1280 px
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(splitter);
  connect(session_, &SessionState::Changed, this, &RobotPanel::Refresh);
}

void RobotPanel::Refresh() {
  if (!session_->IsOpen()) return;
  const Robot& robot = session_->NominalRobot();
  summary_->setText(QString("<b>%1</b> — file <tt>%2</tt>, lengths in %3, Euler %4. Legs as in eq. 3: "
                            "|P + R b<sub>i</sub> − a<sub>i</sub>| = L<sub>i</sub> + l<sub>i</sub>.")
                        .arg(QString::fromStdString(robot.name).toHtmlEscaped(),
                             QString::fromStdString(session_->Config().robot).toHtmlEscaped(),
                             LengthUnitName(robot.length_unit), EulerConventionName(robot.euler)));
  const QString unit = LengthUnitName(robot.length_unit);
  // Coordinates to 1e-4 of the robot unit, the unit in the header (ui/quantity_format.h).
  legs_->setHorizontalHeaderLabels(
      {"a (base, " + unit + ")", "b (platform, " + unit + ")", "offset l (" + unit + ")", "stroke (" + unit + ")"});
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const QStringList cells = {Vec(leg.a_in_base), Vec(leg.b_in_platform), FormatCoordinate(leg.offset),
                               FormatCoordinate(leg.stroke_min) + " … " + FormatCoordinate(leg.stroke_max)};
    for (int c = 0; c < cells.size(); ++c) legs_->setItem(i, c, new QTableWidgetItem(cells[c]));
  }
  view_->Scene().SetRobot(robot);
  if (shown_session_ != session_->Dir()) {  // samples depend on the robot only: once per session
    CandidateOptions options;
    options.count = kWorkspaceSamples;
    StatusOr<CandidateSet> samples = GenerateCandidates(robot, options);
    workspace_samples_ = samples.ok() ? samples->poses : std::vector<Vector6d>{};
  }
  const int planned = static_cast<int>(session_->Plan().size());
  scrub_->setEnabled(planned > 0);
  scrub_->setRange(0, std::max(0, planned - 1));
  UpdateOverlays();
  ShowPlannedPose(scrub_->value());
  if (shown_session_ != session_->Dir()) {  // a refresh keeps the operator's view
    shown_session_ = session_->Dir();
    view_->ResetView();
  }
}

void RobotPanel::ShowPlannedPose(int index) {
  const std::vector<Vector6d>& plan = session_->Plan();
  if (index >= 0 && index < static_cast<int>(plan.size())) {
    if (scrub_->value() != index) scrub_->setValue(index);  // re-enters once with the same index
    view_->Scene().SetPose(plan[index]);
    const Vector6d& p = plan[index];
    scrub_label_->setText(QString("pose %1 of %2: x y z %3 %4 %5 %6, q1 q2 q3 %7 %8 %9°")
                              .arg(index + 1)
                              .arg(plan.size())
                              .arg(FormatCoordinate(p[0]), FormatCoordinate(p[1]), FormatCoordinate(p[2]),
                                   LengthUnitName(session_->NominalRobot().length_unit), FormatCoordinate(p[3]),
                                   FormatCoordinate(p[4]), FormatCoordinate(p[5])));
  } else {
    scrub_label_->setText("no plan: the home pose");
  }
  view_->Render();
}

void RobotPanel::UpdateOverlays() {
  RobotScene& scene = view_->Scene();
  scene.SetGhosts(ghosts_->isChecked() ? session_->Plan() : std::vector<Vector6d>{});
  scene.SetWorkspaceSamples(samples_->isChecked() ? workspace_samples_ : std::vector<Vector6d>{});
  const SessionConfig& config = session_->Config();
  std::optional<CameraTargetFrames> frames;
  if (camera_->isChecked() && config.base_from_camera && config.platform_from_target && session_->SessionCamera() &&
      session_->SessionTarget()) {
    const Robot& robot = session_->NominalRobot();
    frames = CameraTargetFrames{
        *config.base_from_camera, *config.platform_from_target, *session_->SessionCamera(), *session_->SessionTarget(),
        MetresPerUnit(session_->SessionTarget()->length_unit) / MetresPerUnit(robot.length_unit)};
  }
  scene.SetCameraAndTarget(frames);
  view_->Render();
}

}  // namespace hexcal::ui

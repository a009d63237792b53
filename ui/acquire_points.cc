// AcquirePanel in a points session (docs/gui.md, "Acquire in a points
// session"): no camera, the tracker and its own software measure the
// reflectors. Per planned pose the operator moves the robot there, records the
// leg readings, and has the tracker measure the reflectors and export them
// with the pose's name as their group; the checklist reads both back from
// legs.csv and the points file. The camera's layout and actions are in
// acquire_panel.cc and acquire_actions.cc.
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QPushButton>
#include <QStackedWidget>
#include <QTableWidget>
#include <set>

#include "core/point_file.h"
#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/table_cell.h"
#include "workflow/acquire_step.h"
#include "workflow/plan_captures.h"
#include "sim/point_demo_scene.h"
#include "workflow/point_import.h"
#include "workflow/reading_check.h"
#include "session/readings_table.h"
#include "session/session_models.h"
#include "sim/sim_world.h"

namespace hexcal::ui {
namespace {

QString Message(const Status& status) { return QString::fromStdString(status.message()); }

// "✓ done" in green, or "not yet" in grey: a step's state in the guide.
QString Mark(bool done, const QString& done_text) {
  return done ? QString("<span style='color:#007800'>✓ %1</span>").arg(done_text)
              : QString("<span style='color:#777777'>not yet</span>");
}

}  // namespace

void AcquirePanel::ArrangeForInstrument() {
  const bool points = session_->IsPointsSession();
  if (arranged_for_points_ == points) return;
  arranged_for_points_ = points;
  camera_label_->setVisible(!points);
  camera_url_->setVisible(!points);
  right_->setCurrentIndex(points ? 1 : 0);
  capture_->setText(points ? "Record readings" : "Capture");
  capture_->setToolTip(points ? "Record the leg readings at this pose: read from the controller, which moves there "
                                "first, or typed"
                              : "Grab a frame and record it with the leg readings, then go to the next pose");
  redo_->setToolTip(points ? "Record this pose's readings again, replacing those in legs.csv"
                           : "Remove this pose's image and readings and capture it again");
}

// A plan row's readings: a legs.csv row commanded to it (workflow/plan_captures.h);
// its points: the points file has a set named as that row (or as the row it would get).
void AcquirePanel::FillPointChecklist(const std::vector<workflow::ReadingsRow>& rows, const std::vector<int>& found) {
  const std::vector<Vector6d>& plan = session_->Plan();
  has_points_.assign(plan.size(), 0);
  has_readings_.assign(plan.size(), 0);
  std::set<std::string> with_points;
  for (const workflow::ReadingsRow& row : rows)
    if (row.image_present) with_points.insert(row.image);
  checklist_->blockSignals(true);
  checklist_->setRowCount(static_cast<int>(plan.size()));
  for (int k = 0; k < static_cast<int>(plan.size()); ++k) {
    const bool readings = found[k] >= 0;
    const std::string name = readings ? rows[found[k]].image : workflow::CapturePoseName(k, rows);
    free_names_.push_back(name);
    if (readings) captures_[k] = name;
    has_readings_[k] = readings;
    has_points_[k] = with_points.count(name) > 0;
    const bool done = readings && has_points_[k];
    if (readings) marks_.erase(k);
    const QString state = done                ? "✓ recorded"
                          : readings          ? "readings, no points"
                          : has_points_[k]    ? "points, no readings"
                                              : PoseState(k);
    QTableWidgetItem* state_cell = TableCell(state);
    state_cell->setToolTip(QString::fromStdString(name));
    state_cell->setForeground(done ? QColor(0, 120, 0)
                              : state.startsWith("failed") ? QColor(190, 0, 0)
                              : readings || has_points_[k] ? QColor(170, 100, 0)
                                                           : QColor(90, 90, 90));
    SetChecklistRow(k, state_cell, plan[k]);
  }
  checklist_->blockSignals(false);
}

QString AcquirePanel::PointsGuide() const { return guide_->text(); }

bool AcquirePanel::PointPoseDone(int index) const {
  return index >= 0 && index < static_cast<int>(has_points_.size()) && has_points_[index] && has_readings_[index];
}

// The three steps at the selected pose, each with its state.
void AcquirePanel::FillPointsGuide() {
  if (!session_->IsPointsSession()) return;
  if (current_ < 0 || current_ >= static_cast<int>(has_points_.size())) {
    guide_->setText("No planned pose: plan the poses first (Plan step); each is then measured here, one at a time.");
    return;
  }
  const SessionConfig& config = session_->Config();
  const QString name = ImageOfPose(current_).toHtmlEscaped();
  const QString file = QString::fromStdString(config.points).toHtmlEscaped();
  const QString unit = LengthUnitName(session_->NominalRobot().length_unit);
  QString reflectors = "every reflector on the platform (3 or more)";
  if (!config.reflectors.empty()) {
    StatusOr<std::vector<NamedPoint>> listed =
        LoadReflectorFile(session_->Resolve(config.reflectors), config.reflectors);
    QStringList names;
    if (listed.ok())
      for (const NamedPoint& r : *listed) names << QString::fromStdString(r.name).toHtmlEscaped();
    if (!names.isEmpty()) reflectors = QString("the reflectors %1 (%2)").arg(names.join(", ")).arg(config.reflectors.c_str());
  }
  guide_->setText(
      QString("<b>Pose %1 of %2: %3</b><ol>"
              "<li>Move the robot to the pose: <i>Move</i> with a controller, or by hand to the lengths L1..L6 "
              "shown left.</li>"
              "<li>Record the leg readings: <i>Record readings</i> (from the controller, or typed). %4</li>"
              "<li>With the robot still there, measure %5 with the tracker and export them, in %6, with "
              "<b>%3</b> as their group (SpatialAnalyzer's ASCII export: collection group target x y z [σ], "
              "or CSV pose,point,x,y,z[,sigma]): into <b>%7</b>, which is watched, or into any file and "
              "<i>Import points…</i>. %8</li></ol>"
              "A pose with both is recorded, and the checklist goes on to the next.")
          .arg(current_ + 1)
          .arg(has_points_.size())
          .arg(name)
          .arg(Mark(has_readings_[current_], "in legs.csv"), reflectors, unit)
          .arg(file, Mark(has_points_[current_], "in " + file)));
}

void AcquirePanel::RecordPointReadings(const std::optional<LegReadings>& typed, bool again) {
  const QString what = "Record readings";
  if (!session_->IsOpen()) return ShowError(this, what, "Open or create a session first (File menu).");
  if (current_ < 0) return ShowError(this, what, "There is no planned pose: plan first (Plan step).");
  const int index = current_;
  if (!again && has_readings_[index])
    return SetOutcome(QString("pose %1 has its readings in legs.csv: Redo records them again.").arg(index + 1));
  if (rig_ && rig_->controller && !typed) {
    if (!ReadyToAct(what, [this, again] { RecordPointReadings(std::nullopt, again); })) return;
    const Vector6d pose = session_->Plan()[index];
    SetOutcome(QString("moving to pose %1 and reading the legs…").arg(index + 1));
    job_->Start("reading", [this, rig = rig_, pose, index, again](const JobContext&) -> GuiContinuation {
      Status moved = rig->controller->MoveTo(pose);
      if (moved.ok()) moved = rig->controller->WaitSettled(rig->controller->DefaultSettleSeconds());
      StatusOr<LegReadings> legs = moved.ok() ? rig->controller->ReadLegs() : StatusOr<LegReadings>(moved);
      return [this, legs, index, again] {
        if (!legs.ok()) return Recorded(index, legs.status());
        moved_to_ = index;
        SavePointReadings(index, *legs, again, /*from_controller=*/true);
      };
    });
    return;
  }
  if (job_->Running() && !job_->Abandoned() && job_->What() != "live")
    return ShowError(this, what, "The controller is busy: wait for the current step, or press Cancel.");
  const std::optional<LegReadings> readings = typed ? typed : AskReadings(index);
  if (!readings) return SetOutcome("not recorded: no readings entered.");
  SavePointReadings(index, *readings, again, /*from_controller=*/false);
}

void AcquirePanel::SavePointReadings(int index, const LegReadings& readings, bool overwrite, bool from_controller) {
  const Vector6d pose = session_->Plan()[index];
  const std::string name = ImageOfPose(index).toStdString();
  // Against the stroke and the commanded pose's IK lengths (reading_check.h).
  const workflow::ReadingCheck check = workflow::MakeReadingCheck(session_->NominalRobot(), session_->Config().noise);
  const Status plausible = from_controller ? workflow::CheckReadings(check, name, pose, readings)
                                           : workflow::CheckTypedReadings(check, name, readings, pose);
  if (!plausible.ok()) {
    SetOutcome("not recorded: " + Message(plausible));
    return ShowError(this, "Record readings", Message(plausible) + "\nRecord them again and check the readings.");
  }
  LegsRow row;
  row.image = name;
  row.legs = readings;
  row.commanded = pose;  // ties the row to this planned pose (workflow/plan_captures.h)
  const bool saved = ApplySessionEdit(this, "Record readings", [&](bool overwrite_theirs) {
    return session_->EditLegs(workflow::LegsEdit::SetRow(row), overwrite || overwrite_theirs);
  });
  if (!saved) return SetOutcome("not recorded: legs.csv is as it was.");
  PointPoseSaved(index, QString("pose %1: readings saved to legs.csv as %2.").arg(index + 1).arg(name.c_str()));
}

void AcquirePanel::ImportPoints(const QString& chosen) {
  const QString what = "Import points";
  if (!session_->IsPointsSession()) return ShowError(this, what, "Open a points session first (File menu).");
  if (current_ < 0) return ShowError(this, what, "There is no planned pose: plan first (Plan step).");
  const int index = current_;
  const QString file = !chosen.isEmpty() ? chosen
                                         : QFileDialog::getOpenFileName(this, "Import the tracker's points",
                                                                        session_->Dir(),
                                                                        "Tracker exports (*.txt *.csv *.asc);;All files (*)");
  if (file.isEmpty()) return;
  const std::string dir = session_->Dir().toStdString();
  StatusOr<workflow::PointImport> import =
      workflow::ReadPointImport(dir, file.toStdString(), ImageOfPose(index).toStdString());
  if (!import.ok()) return ShowError(this, what, session_->InSession(Message(import.status())));
  const QString points_file = QString::fromStdString(session_->Config().points);
  if (!import->replaced.empty()) {
    QStringList names;
    for (const std::string& pose : import->replaced) names << QString::fromStdString(pose);
    const int answer = AskChoice(this, what, QString("%1 has points of %2 already.").arg(points_file, names.join(", ")),
                                 "Replace them with those of " + QFileInfo(file).fileName() + "?",
                                 {"Replace", "Cancel"}, 1);
    if (answer != 0) return SetOutcome("not imported: " + points_file + " is as it was.");
  }
  if (Status s = workflow::WritePointImport(dir, *import, /*replace=*/true); !s.ok())
    return ShowError(this, what, session_->InSession(Message(s)));
  const QString imported =
      import->sets.size() == 1
          ? QString("%1 points of %2").arg(import->sets[0].points.size()).arg(import->sets[0].pose.c_str())
          : QString("%1 point sets").arg(import->sets.size());
  PointPoseSaved(index, QString("%1 imported from %2 into %3.").arg(imported, QFileInfo(file).fileName(), points_file));
}

void AcquirePanel::MeasureWithSimTracker() {
  const QString what = "Sim tracker";
  if (!rig_ || !rig_->sim)
    return ShowError(this, what, "Connect the sim controller first: the sim tracker measures its platform.");
  if (current_ < 0) return ShowError(this, what, "There is no planned pose: plan first (Plan step).");
  if (job_->Running() && !job_->Abandoned() && job_->What() != "live")
    return ShowError(this, what, "The controller is busy: wait for the current step, or press Cancel.");
  const int index = current_;
  // The reflectors are where the platform is: at another pose they would not be this pose's.
  if (moved_to_ != index)
    return ShowError(this, what, QString("The sim platform is not at pose %1: Move there first (or Record readings, "
                                         "which moves there).").arg(index + 1));
  const double sigma = session_->Config().point_sigma;
  if (!(sigma > 0)) return ShowError(this, what, "session.yaml's point_sigma is not positive: the sim tracker needs it.");
  const std::string name = ImageOfPose(index).toStdString();
  const workflow::PointImport import{
      {workflow::SimTrackerMeasure(*rig_->sim, sigma, name, static_cast<uint64_t>(++sim_tracker_draws_))}, {}, {}};
  if (Status s = workflow::WritePointImport(session_->Dir().toStdString(), import, /*replace=*/true); !s.ok())
    return ShowError(this, what, session_->InSession(Message(s)));
  PointPoseSaved(index, QString("pose %1: %2 points measured by the sim tracker, saved to %3.")
                            .arg(index + 1)
                            .arg(import.sets[0].points.size())
                            .arg(session_->Config().points.c_str()));
}

// Refresh, from the reload, marks the pose and moves on when it has both;
// otherwise the line says what the pose still needs.
void AcquirePanel::PointPoseSaved(int index, const QString& done) {
  const bool was_done = PointPoseDone(index);
  session_->Reload();
  if (PointPoseDone(index)) return SetOutcome(was_done ? done : done + " " + outcome_);
  const QString name = ImageOfPose(index);
  SetOutcome(done + " " +
             (has_readings_[index]
                  ? QString("Now measure its reflectors with the tracker and export them as group %1 (or Import "
                            "points…).").arg(name)
                  : QString("Now record its leg readings (Record readings).")));
}

// Called by Refresh: a pose whose readings or points (another program's
// export) just completed it is marked, and the next pose selected.
void AcquirePanel::AdvanceWhenRecorded(int index, bool was_done) {
  if (!session_->IsPointsSession() || index < 0 || was_done || !PointPoseDone(index) || current_ != index) return;
  const bool more = NextPose();
  SetOutcome(QString("pose %1 recorded (readings and points).%2")
                 .arg(index + 1)
                 .arg(more ? QString(" Next: pose %1.").arg(current_ + 1) : QString(" ") + kAllDone));
}

}  // namespace hexcal::ui

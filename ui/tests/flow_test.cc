// The whole GUI flow on a fresh copy of the test session (make_session):
// open it, plan, delete a pose, cancel a plan, load the rendered images,
// measure, look at one image's detection, calibrate, validate, export, and a
// screenshot of every panel. Run under xvfb-run (ui/CMakeLists.txt).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QScrollBar>
#include <QSurfaceFormat>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTextBrowser>
#include <QTextCursor>
#include <QTextDocument>
#include <QThread>
#include <algorithm>
#include <functional>

#include "core/candidates.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "report/calibration_verdict.h"
#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/calibrate_panel.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/help_browser.h"
#include "ui/image_overlay.h"
#include "ui/image_view.h"
#include "ui/main_window.h"
#include "ui/measure_panel.h"
#include "ui/plan_options.h"
#include "ui/plan_panel.h"
#include "ui/plan_visibility.h"
#include "ui/quantity_format.h"
#include "ui/readings_editor.h"
#include "ui/robot_panel.h"
#include "ui/robot_scene.h"
#include "ui/robot_view.h"
#include "ui/screenshot.h"
#include "ui/tests/gui_test_support.h"
#include "ui/validate_panel.h"
#include "ui/verdict_view.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/plan_step.h"

namespace hexcal::ui {
namespace {

QString sessions_dir;  // argv[1]: what make_session wrote

std::string ReadTextFile(const std::string& path) {
  QFile file(QString::fromStdString(path));
  return file.open(QIODevice::ReadOnly) ? file.readAll().toStdString() : std::string();
}

void WriteTextFile(const std::string& path, const std::string& text) {
  QFile file(QString::fromStdString(path));
  if (file.open(QIODevice::WriteOnly | QIODevice::Truncate)) file.write(text.data(), static_cast<qint64>(text.size()));
}

int CsvRows(const QString& path) {
  StatusOr<CsvTable> table = ReadCsv(path.toStdString());
  return table.ok() ? static_cast<int>(table->rows.size()) : -1;
}

// Validate: before and after on the 4 held-out images, the verdict, exports.
void CheckValidatePanel(ValidatePanel* validate, const QString& level, const QTemporaryDir& temp) {
  EXPECT_EQ(validate->VerdictWidget()->LevelText(), level);
  bool number = false;
  // "0.0424 cm": the figure, then its unit.
  const QString before_text = validate->SummaryTable()->item(0, 0)->text();
  EXPECT_TRUE(before_text.endsWith(" cm")) << before_text.toStdString();
  const double before = before_text.section(' ', 0, 0).toDouble(&number);
  EXPECT_TRUE(number);
  const double after = validate->SummaryTable()->item(0, 1)->text().section(' ', 0, 0).toDouble(&number);
  EXPECT_TRUE(number);
  EXPECT_GT(before, 0);
  EXPECT_LT(after, before);  // the true robot differs from the nominal one
  validate->ExportCalibratedRobot(temp.filePath("calibrated.yaml"));
  EXPECT_TRUE(QFile::exists(temp.filePath("calibrated.yaml")));
  validate->ExportHtmlReport(temp.filePath("report.html"));
  EXPECT_TRUE(QFile::exists(temp.filePath("report.html")));
}

TEST(UiFlow, PlanMeasureCalibrateValidate) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  SessionState& session = *window.Session();
  EXPECT_EQ(session.State(Step::kRobot), StepState::kDone);
  EXPECT_EQ(session.State(Step::kPlan), StepState::kTodo);
  // legs.csv names images that are not loaded yet: the session says so.
  EXPECT_TRUE(session.LegsError().contains("is not in images/")) << session.LegsError().toStdString();

  // Plan: a small run, then the table, the file and the 3D view follow.
  PlanPanel* plan = window.Plan();
  plan->Options()->SetValue("poses", 8);
  plan->Options()->SetValue("candidate_count", 300);
  plan->Options()->SetText("candidate_kind", "random");  // the boundary set's homotopy FK costs seconds
  plan->Options()->SetValue("iterations", 20);
  plan->Run();
  ASSERT_TRUE(WaitFor([&] { return !plan->Job()->Running(); }));
  EXPECT_TRUE(plan->LastOutcome().startsWith("done")) << plan->LastOutcome().toStdString();
  EXPECT_TRUE(plan->LastOutcome().contains("expected mean error")) << plan->LastOutcome().toStdString();
  EXPECT_TRUE(plan->LastOutcome().contains("S-efficiency ≥")) << plan->LastOutcome().toStdString();
  EXPECT_EQ(session.Plan().size(), 8u);
  EXPECT_EQ(plan->PoseTable()->rowCount(), 8);
  EXPECT_EQ(CsvRows(dir + "/plan.csv"), 8);
  EXPECT_GT(CsvRows(dir + "/plan_history.csv"), 1);
  EXPECT_EQ(session.State(Step::kPlan), StepState::kDone);

  // Delete the first pose: the indices are renumbered 1..7 and plan.csv follows.
  plan->PoseTable()->sortItems(0);
  plan->PoseTable()->selectRow(0);
  plan->DeleteSelectedPoses();
  EXPECT_EQ(plan->PoseTable()->rowCount(), 7);
  EXPECT_EQ(CsvRows(dir + "/plan.csv"), 7);
  for (int r = 0; r < 7; ++r) EXPECT_EQ(plan->PoseTable()->item(r, 0)->data(Qt::DisplayRole).toInt(), r + 1);
  plan->AddPose();
  EXPECT_EQ(plan->PoseTable()->rowCount(), 8);
  window.Robot()->ShowPlannedPose(7);

  // Cancel: a long plan stops and leaves the plan as it was.
  plan->Options()->SetValue("iterations", 100000);
  plan->Options()->SetValue("tabu", 3);
  plan->Run();
  plan->Cancel();
  ASSERT_TRUE(WaitFor([&] { return !plan->Job()->Running(); }));
  EXPECT_TRUE(plan->LastOutcome().startsWith("cancelled")) << plan->LastOutcome().toStdString();
  EXPECT_EQ(session.Plan().size(), 8u);

  // Measure: load the rendered images, then legs.csv loads; measure them all.
  MeasurePanel* measure = window.Measure();
  measure->LoadImageFolder(sessions_dir + "/rendered");
  EXPECT_TRUE(session.LegsError().isEmpty()) << session.LegsError().toStdString();
  EXPECT_EQ(measure->ImageList()->count(), 16);
  EXPECT_EQ(measure->LegsTable()->rowCount(), 16);
  measure->MeasureAll();
  ASSERT_TRUE(WaitFor([&] { return !measure->Job()->Running(); }));
  EXPECT_EQ(CsvRows(dir + "/camera_poses.csv"), 16);
  EXPECT_EQ(session.State(Step::kMeasure), StepState::kDone);
  EXPECT_TRUE(measure->ImageList()->item(0)->text().contains("ok"))
      << measure->ImageList()->item(0)->text().toStdString();
  measure->ImageList()->setCurrentRow(1);
  ASSERT_TRUE(WaitFor([&] { return !measure->PreviewJob()->Running(); }));
  EXPECT_TRUE(measure->ShownStatus().startsWith("ok")) << measure->ShownStatus().toStdString();

  // Calibrate: 42 parameters; the steps after it are done.
  CalibratePanel* calibrate = window.Calibrate();
  calibrate->Run();
  ASSERT_TRUE(WaitFor([&] { return !calibrate->Job()->Running(); }));
  EXPECT_TRUE(calibrate->LastOutcome().startsWith("done")) << calibrate->LastOutcome().toStdString();
  EXPECT_EQ(calibrate->ParameterTable()->rowCount(), 42);
  EXPECT_EQ(session.State(Step::kCalibrate), StepState::kDone);
  EXPECT_EQ(session.State(Step::kValidate), StepState::kDone);
  // The verdict the CLI prints, on both panels (report/calibration_verdict.h).
  ASSERT_TRUE(session.Results().ok());
  const QString level = workflow::VerdictLevelName(workflow::MakeVerdict(session.Results()->report).level);
  EXPECT_EQ(calibrate->VerdictWidget()->LevelText(), level);

  CheckValidatePanel(window.Validate(), level, temp);

  // An edited reading makes the calibration stale.
  QThread::msleep(1100);  // file times have a 1 s resolution on some file systems
  const double reading = measure->LegsTable()->item(0, 1)->text().toDouble();
  measure->LegsTable()->item(0, 1)->setText(QString::number(reading + 0.001, 'g', 10));
  EXPECT_NEAR(session.Legs()[0].legs[0], reading + 0.001, 1e-9);
  EXPECT_EQ(session.State(Step::kCalibrate), StepState::kStale);

  // Every panel renders, the 3D view included.
  for (const char* panel : {"robot", "plan", "measure", "calibrate", "validate"}) {
    ASSERT_TRUE(window.ShowPanelNamed(panel));
    const QString file = temp.filePath(QString(panel) + ".png");
    EXPECT_TRUE(SaveWindowScreenshot(&window, file)) << panel;
    EXPECT_GT(QFileInfo(file).size(), 10000) << panel;
  }
  const QImage view = window.Robot()->View()->Snapshot();
  EXPECT_GT(view.width(), 100);
}

TEST(UiFlow, ClosingTheWindowCancelsARunningJob) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  const std::vector<Vector6d> plan_before = [&] {
    MainWindow window;
    EXPECT_TRUE(window.OpenSession(dir));
    return window.Session()->Plan();
  }();
  QElapsedTimer timer;
  timer.start();
  {
    MainWindow window;
    ASSERT_TRUE(window.OpenSession(dir));
    window.Plan()->Options()->SetValue("iterations", 100000);
    window.Plan()->Options()->SetValue("tabu", 3);
    window.Plan()->Run();
    ASSERT_TRUE(window.Plan()->Job()->Running());
    QThread::msleep(200);
  }  // the window dies with the job running: cancelled and joined, no crash
  EXPECT_LT(timer.elapsed(), 20000);
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  EXPECT_EQ(window.Session()->Plan().size(), plan_before.size());
}

TEST(UiFlow, IntrinsicsFromTargetImages) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  MeasurePanel* measure = window.Measure();
  measure->IntrinsicsFromFolder(sessions_dir + "/rendered");
  ASSERT_TRUE(WaitFor([&] { return !measure->Job()->Running(); }));
  EXPECT_EQ(window.Session()->Config().camera, "camera.yaml");
  ASSERT_TRUE(window.Session()->SessionCamera().has_value());
  EXPECT_NEAR(window.Session()->SessionCamera()->width, 1024, 0);
  const auto* report = measure->findChild<QPlainTextEdit*>("intrinsics_report");
  ASSERT_NE(report, nullptr);
  // Each figure with its unit (issue 35): "of 16 views used", "fx 903.5 px".
  const QString text = report->toPlainText();
  EXPECT_TRUE(text.contains("of 16 views used")) << text.toStdString();
  EXPECT_TRUE(text.contains(QRegularExpression("fx [0-9]+\\.[0-9] px, fy [0-9]+\\.[0-9] px"))) << text.toStdString();
  // The "intrinsics…" line of the job's start does not outlive it.
  auto* status = measure->findChild<QLabel*>("measure_status");
  ASSERT_NE(status, nullptr);
  EXPECT_FALSE(status->text().endsWith("…")) << status->text().toStdString();
  EXPECT_TRUE(status->text().contains("camera.yaml written")) << status->text().toStdString();
}

// Another program writes the session while the window is open (issue 13): the
// window shows it, an operator's edit is applied to the file as it is on
// disk, a clash on the same cell keeps the other program's value (no one to
// ask in a test), and quitting writes nothing: every byte of theirs survives.
TEST(UiFlow, ExternalChangesSurviveEditsAndQuit) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  const std::string s = dir.toStdString();
  auto window = std::make_unique<MainWindow>();
  ASSERT_TRUE(window->OpenSession(dir));
  const std::vector<LegsRow> shown = window->Session()->Legs();
  ASSERT_GE(shown.size(), 2u);

  // The other program: a new plan, a new image with its row, another noise model.
  const std::vector<Vector6d> their_plan(3, window->Session()->Plan().front());
  ASSERT_TRUE(workflow::WritePlanCsv(s + "/plan.csv", PlanningModel{window->Session()->NominalRobot(), {}, {}},
                                     their_plan).ok());
  QFile::copy(dir + "/images/" + QString::fromStdString(shown[0].image), dir + "/images/theirs.png");
  QFile legs(dir + "/legs.csv");
  ASSERT_TRUE(legs.open(QIODevice::Append));
  legs.write(("theirs.png," + ReadCsv(s + "/legs.csv")->rows[0][1] + ",1,2,3,4,5,0\n").c_str());
  legs.close();
  const std::string legs_theirs = ReadTextFile(s + "/legs.csv");
  SessionConfig config = *LoadSessionConfig(s);
  config.noise.leg *= 2;
  ASSERT_TRUE(SaveSessionConfig(s, config).ok());
  const std::string config_theirs = ReadTextFile(s + "/session.yaml");

  // The folder watch reloads: the new row is on screen.
  auto* table = window->Measure()->findChild<QTableWidget*>("legs_table");
  ASSERT_NE(table, nullptr);
  ASSERT_TRUE(WaitFor([&] { return table->rowCount() == static_cast<int>(shown.size()) + 1; }, 10000));
  EXPECT_EQ(window->Session()->Plan().size(), 3u);

  // The operator types L1 of the first image: applied to the file on disk.
  table->item(0, 1)->setText("1.75");  // within the stroke, 0..3.5 cm
  StatusOr<CsvTable> after_edit = ReadCsv(s + "/legs.csv");
  ASSERT_TRUE(after_edit.ok());
  EXPECT_EQ(after_edit->rows.size(), shown.size() + 1);
  EXPECT_EQ(after_edit->rows.back()[0], "theirs.png");
  EXPECT_NEAR(*ParseNumber(after_edit->rows[0][1]), 1.75, 1e-9);

  // The same cell changed on disk under the operator's next edit: theirs stays.
  const std::string legs_before_clash = ReadTextFile(s + "/legs.csv");
  std::string clashed = legs_before_clash;
  const std::string old_cell = after_edit->rows[1][2];
  clashed.replace(clashed.find("," + old_cell + ","), old_cell.size() + 2, ",99.5,");
  WriteTextFile(s + "/legs.csv", clashed);
  table->item(1, 2)->setText("2.5");
  EXPECT_EQ(ReadTextFile(s + "/legs.csv"), clashed);

  window.reset();  // quit: nothing is written back
  EXPECT_EQ(ReadTextFile(s + "/legs.csv"), clashed);
  EXPECT_EQ(ReadTextFile(s + "/session.yaml"), config_theirs);
  EXPECT_EQ(LoadPoses(s + "/plan.csv")->size(), 3u);
  (void)legs_theirs;
}

// A file name is shown as it is, never as HTML (issue 13): legs.csv naming an
// image "<b>bold</b>.png" that is not in images/ gives an error quoting it.
TEST(UiFlow, FileNamesAreShownAsPlainText) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  QFile legs(dir + "/legs.csv");
  ASSERT_TRUE(legs.open(QIODevice::Append));
  legs.write("<b>bold</b>.png,1,2,3,4,5,6,0\n");
  legs.close();
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  auto* status = window.Measure()->findChild<QLabel*>("measure_status");
  ASSERT_NE(status, nullptr);
  EXPECT_TRUE(status->text().contains("<b>bold</b>.png")) << status->text().toStdString();
  EXPECT_EQ(status->textFormat(), Qt::PlainText);
}

// Opening another session (issue 15): nothing of the previous one stays on
// screen — image, texts, options, a job's result — and the step list is the
// new session's.
TEST(UiFlow, ASessionSwitchLeavesNothingOfThePreviousSession) {
  QTemporaryDir temp;
  const QString first = temp.filePath("first"), second = temp.filePath("second");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", first));
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.camera = kSimulatedCameraName;
  config.target = kDefaultTargetName;
  config.robot = "deltalab-table";  // in mm: the Calibrate headers must say so
  ASSERT_TRUE(InitSession(second.toStdString(), config).ok());
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(first));
  // The Acquire step on pose 3 of the first session's plan, with another controller chosen.
  AcquirePanel* acquire = window.Acquire();
  acquire->SelectPose(2);
  auto* pose = acquire->findChild<QLabel*>("acquire_pose");
  ASSERT_NE(pose, nullptr);
  EXPECT_TRUE(pose->text().startsWith("pose 3 of 12")) << pose->text().toStdString();
  auto* controller = acquire->findChild<QComboBox*>("acquire_controller");
  ASSERT_NE(controller, nullptr);
  controller->setCurrentText("linuxcnc://localhost:5007");
  EXPECT_TRUE(window.Calibrate()->ParameterTable()->horizontalHeaderItem(2)->text().endsWith("(cm)"));
  MeasurePanel* measure = window.Measure();
  measure->ImageList()->setCurrentRow(1);
  ASSERT_TRUE(WaitFor([&] { return !measure->PreviewJob()->Running(); }));
  ASSERT_TRUE(measure->Picture()->HasImage());
  window.Plan()->Options()->SetValue("poses", 9);
  window.Plan()->Visibility()->Choose("session");
  measure->MeasureAll();  // still running when the other session opens
  ASSERT_TRUE(measure->Job()->Running());

  ASSERT_TRUE(window.OpenSession(second));
  ASSERT_TRUE(WaitFor([&] { return !measure->Job()->Running(); }));
  EXPECT_FALSE(measure->Picture()->HasImage());
  EXPECT_EQ(measure->ImageList()->count(), 0);
  EXPECT_EQ(measure->LegsTable()->rowCount(), 0);
  auto* status = measure->findChild<QLabel*>("measure_status");
  ASSERT_NE(status, nullptr);
  EXPECT_TRUE(status->text().isEmpty()) << status->text().toStdString();  // no "measured 16 images"
  StatusOr<workflow::PlanSetup> options = window.Plan()->Options()->Options();
  ASSERT_TRUE(options.ok());
  EXPECT_EQ(options->planner.num_poses, workflow::PlanSetup{}.planner.num_poses);
  StatusOr<std::optional<MeasurementConstraints>> visibility = window.Plan()->Visibility()->Constraints();
  ASSERT_TRUE(visibility.ok());
  EXPECT_FALSE(visibility->has_value());
  EXPECT_EQ(window.Calibrate()->ParameterTable()->rowCount(), 0);
  for (int column = 2; column <= 5; ++column)  // nominal, calibrated, change, σ: this session's unit
    EXPECT_TRUE(window.Calibrate()->ParameterTable()->horizontalHeaderItem(column)->text().endsWith("(mm)"))
        << window.Calibrate()->ParameterTable()->horizontalHeaderItem(column)->text().toStdString();
  // The Acquire step: no pose or lengths of the last plan, the default devices again.
  EXPECT_EQ(pose->text(), "no pose");
  EXPECT_EQ(acquire->CurrentPose(), -1);
  EXPECT_EQ(acquire->ControllerChoice(), "sim");
  EXPECT_EQ(acquire->CameraChoice(), "sim");
  EXPECT_EQ(acquire->Checklist()->rowCount(), 0);
  EXPECT_EQ(window.Session()->State(Step::kRobot), StepState::kDone);
  for (Step step : {Step::kPlan, Step::kMeasure, Step::kCalibrate, Step::kValidate})
    EXPECT_EQ(window.Session()->State(step), StepState::kTodo) << StepName(step);
  auto* steps = window.findChild<QListWidget*>("step_list");
  ASSERT_NE(steps, nullptr);
  EXPECT_TRUE(steps->item(static_cast<int>(Step::kMeasure))->text().startsWith("○"));
}

// New intrinsics (issue 15): Measure and Calibrate become stale in the step
// list, and calibrating measures every image again with the new camera.
TEST(UiFlow, NewIntrinsicsAreStaleAndTheCalibrationMeasuresAgain) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  SessionState& session = *window.Session();
  for (int k = 0; k < kNumSteps; ++k)
    EXPECT_EQ(session.State(static_cast<Step>(k)), StepState::kDone) << StepName(static_cast<Step>(k));
  StatusOr<Camera> camera = LoadCamera(session.Config().camera);
  ASSERT_TRUE(camera.ok());
  camera->fx *= 1.01;
  camera->fy *= 1.01;
  ASSERT_TRUE(SaveCamera(*camera, (dir + "/camera.yaml").toStdString()).ok());
  ASSERT_TRUE(ApplySessionEdit(&window, "Intrinsics", [&](bool overwrite) {
    return session.SetCamera("camera.yaml", overwrite);
  }));
  EXPECT_EQ(session.State(Step::kMeasure), StepState::kStale);
  EXPECT_EQ(session.State(Step::kCalibrate), StepState::kStale);
  auto* steps = window.findChild<QListWidget*>("step_list");
  ASSERT_NE(steps, nullptr);
  QListWidgetItem* measure_row = steps->item(static_cast<int>(Step::kMeasure));
  EXPECT_TRUE(measure_row->text().startsWith("⟳"));
  EXPECT_TRUE(measure_row->toolTip().contains("the camera changed")) << measure_row->toolTip().toStdString();
  // The image list no longer says "ok" for measurements made with the old camera.
  QListWidget* images = window.Measure()->ImageList();
  ASSERT_GT(images->count(), 0);
  for (int row = 0; row < images->count(); ++row) {
    EXPECT_FALSE(images->item(row)->text().contains("—  ok")) << images->item(row)->text().toStdString();
    EXPECT_TRUE(images->item(row)->text().endsWith("to measure again")) << images->item(row)->text().toStdString();
    EXPECT_TRUE(images->item(row)->toolTip().contains("the camera changed"))
        << images->item(row)->toolTip().toStdString();
  }

  const std::string before = ReadTextFile((dir + "/camera_poses.csv").toStdString());
  window.Calibrate()->Run();
  ASSERT_TRUE(WaitFor([&] { return !window.Calibrate()->Job()->Running(); }));
  EXPECT_TRUE(window.Calibrate()->LastOutcome().startsWith("done")) << window.Calibrate()->LastOutcome().toStdString();
  EXPECT_NE(ReadTextFile((dir + "/camera_poses.csv").toStdString()), before);
  for (int k = 0; k < kNumSteps; ++k)
    EXPECT_EQ(session.State(static_cast<Step>(k)), StepState::kDone) << StepName(static_cast<Step>(k));
  EXPECT_TRUE(images->item(0)->text().contains("—  ok")) << images->item(0)->text().toStdString();
  // The progress bar and the run's line do not outlive the job: the bar goes
  // with it, the line with the results it describes (a reading edited).
  for (QProgressBar* bar : window.findChildren<QProgressBar*>()) EXPECT_TRUE(bar->isHidden());
  const LegsRow& first = session.Legs().front();
  ASSERT_TRUE(ApplySessionEdit(&window, "Leg readings", [&](bool overwrite) {
    return session.EditLegs(workflow::LegsEdit::SetReading(first.image, 0, first.legs[0], first.legs[0] + 0.001),
                            overwrite);
  }));
  EXPECT_TRUE(window.Calibrate()->LastOutcome().startsWith("Results stale: legs.csv changed"))
      << window.Calibrate()->LastOutcome().toStdString();
}

// Loaded images without readings get rows to type or paste them into.
TEST(UiFlow, ImagesWithoutReadingsGetRowsToTypeAndPasteInto) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  QFile::remove(dir + "/legs.csv");
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  MeasurePanel* measure = window.Measure();
  measure->LoadImageFolder(sessions_dir + "/rendered");
  ReadingsEditor* table = measure->LegsTable();
  ASSERT_EQ(table->rowCount(), 16);
  EXPECT_EQ(table->MissingRows(), 16);
  auto* hint = measure->findChild<QLabel*>("readings_hint");
  ASSERT_NE(hint, nullptr);
  EXPECT_TRUE(hint->text().contains("16 image(s) have no readings yet")) << hint->text().toStdString();
  for (int i = 0; i < kNumLegs; ++i) table->item(0, 1 + i)->setText(QString::number(1 + 0.1 * i));  // cm
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 1);
  EXPECT_EQ(table->PasteReadings("2.0\t2.1\t2.2\t2.3\t2.4\t2.5\n3.0,3.1,3.2,3.3,3.4,3.5\n", 1), 2);
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 3);
  EXPECT_EQ(table->MissingRows(), 13);
  // Calibrating now names what is missing and how to enter it.
  EXPECT_TRUE(window.Session()->LegsError().contains("enter the six leg readings"))
      << window.Session()->LegsError().toStdString();
}

// A boundary pose's readings sit on the stroke ends up to round-off: the 3D
// view does not call them beyond the stroke; a real excess is.
TEST(UiFlow, TheStrokeCheckHasTheFeasibilityTolerance) {
  StatusOr<Robot> robot = LoadRobot("inria-left-hand");
  ASSERT_TRUE(robot.ok());
  CandidateOptions boundary;
  boundary.kind = CandidateKind::kBoundary;
  StatusOr<CandidateSet> poses = GenerateCandidates(*robot, boundary);
  ASSERT_TRUE(poses.ok());
  ASSERT_FALSE(poses->poses.empty());
  RobotScene scene;
  scene.SetRobot(*robot);
  for (const Vector6d& pose : poses->poses) {
    scene.SetPose(pose);
    for (int i = 0; i < kNumLegs; ++i) EXPECT_FALSE(scene.LegBeyondStroke()[i]) << "leg " << i + 1;
  }
  Robot shorter = *robot;
  shorter.legs[0].stroke_max = InverseKinematics(*robot, robot->PoseFromVector(poses->poses[0]))[0] - 1e-3;
  scene.SetRobot(shorter);
  scene.SetPose(poses->poses[0]);
  EXPECT_TRUE(scene.LegBeyondStroke()[0]);
}

// Help shows docs/ in the application; the detection overlay zooms.
TEST(UiFlow, HelpPagesAndImageZoom) {
  HelpBrowser help;
  help.show();
  ASSERT_TRUE(help.ShowPage("gui.md")) << DocsFolder().toStdString();
  EXPECT_TRUE(help.ShownText().contains("Measure")) << help.ShownText().left(200).toStdString();
  // Its screenshots load (issue 35: every one was a broken image), no wider than the page.
  EXPECT_GE(help.Images().size(), 8);
  EXPECT_EQ(help.MissingImages(), QStringList{});
  if (const QString shots = qEnvironmentVariable("HEXCAL_GUI_SHOTS"); !shots.isEmpty()) {
    // docs/images/gui-help.png: the Robot section, its screenshot in the page.
    auto* text = help.findChild<QTextBrowser*>("help_text");
    ASSERT_NE(text, nullptr);
    help.resize(900, 640);
    QTextCursor at = text->document()->find("The nominal robot of the session");
    ASSERT_FALSE(at.isNull());
    Settle();
    text->verticalScrollBar()->setValue(static_cast<int>(text->cursorRect(at).top()) +
                                        text->verticalScrollBar()->value() - 560);
    Settle();
    EXPECT_TRUE(help.grab().save(shots + "/gui-help.png"));
  }
  // A link to another page, and Back.
  EXPECT_FALSE(help.CanGoBack());
  help.FollowLink("acquisition.md#readings-that-are-plausible-or-refused");
  EXPECT_EQ(help.ShownPage(), "acquisition.md");
  EXPECT_TRUE(help.ShownText().contains("controller")) << help.ShownText().left(200).toStdString();
  ASSERT_TRUE(help.CanGoBack());
  help.Back();
  EXPECT_EQ(help.ShownPage(), "gui.md");
  EXPECT_FALSE(help.ShowPage("no-such-page.md"));
  // The Help menu has the acquisition page.
  MainWindow window;
  QStringList entries;
  for (QAction* menu : window.menuBar()->actions())
    if (menu->menu() && menu->text() == "&Help")
      for (QAction* entry : menu->menu()->actions()) entries << entry->text();
  EXPECT_TRUE(entries.join("|").contains("&Acquisition")) << entries.join("|").toStdString();
  ImageView view;
  view.resize(400, 300);
  view.show();
  QImage image(800, 600, QImage::Format_RGB32);
  image.fill(Qt::gray);
  view.SetImage(image);
  const double fitted = view.Zoom();
  EXPECT_NEAR(fitted, 0.5, 0.05);
  view.ZoomBy(4);
  EXPECT_NEAR(view.Zoom(), 4 * fitted, 1e-9);
  view.SetImage(image);  // a live view's next frame keeps the zoom
  EXPECT_NEAR(view.Zoom(), 4 * fitted, 1e-9);
  view.Fit();
  EXPECT_NEAR(view.Zoom(), fitted, 1e-9);
}

// The Acquire step through the simulated controller and camera (issue 15):
// the live view's readiness, capture pose by pose, skip, run the rest, redo;
// then by hand (camera only, readings typed); the session is written after
// every pose and calibrates.
TEST(UiFlow, AcquisitionWalksThePlanWithTheSimulatedCamera) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  QFile::remove(dir + "/legs.csv");
  ASSERT_TRUE(QFile::copy(sessions_dir + "/calibrated/plan.csv", dir + "/plan.csv"));
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  ASSERT_TRUE(window.ShowPanelNamed("acquire"));
  AcquirePanel* acquire = window.Acquire();
  const int poses = static_cast<int>(window.Session()->Plan().size());
  ASSERT_EQ(acquire->Checklist()->rowCount(), poses);
  EXPECT_EQ(acquire->CurrentPose(), 0);
  EXPECT_EQ(window.Session()->State(Step::kAcquire), StepState::kTodo);
  // The default devices are a pair that connects; without devices, or
  // without a controller, the buttons that need them are disabled.
  EXPECT_EQ(acquire->ControllerChoice(), "sim");
  EXPECT_EQ(acquire->CameraChoice(), "sim");
  const auto button = [&](const char* name) { return acquire->findChild<QPushButton*>(name); };
  for (const char* name : {"acquire_capture", "acquire_redo", "acquire_move", "acquire_run_the_rest"}) {
    ASSERT_NE(button(name), nullptr) << name;
    EXPECT_FALSE(button(name)->isEnabled()) << name;
  }
  // The sim camera without the sim controller: said in the panel's terms.
  acquire->Connect("none", "sim");
  EXPECT_FALSE(acquire->Connected());
  EXPECT_TRUE(LastShownError().contains("choose 'sim' in the Controller list")) << LastShownError().toStdString();
  EXPECT_FALSE(LastShownError().contains("--")) << LastShownError().toStdString();

  acquire->Connect("sim", "sim");
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected(); }));
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LiveView()->HasImage());
  EXPECT_TRUE(acquire->LastFrame().ok) << acquire->LastFrame().status.toStdString();
  EXPECT_TRUE(ReadinessProblem(acquire->LastFrame()).isEmpty()) << ReadinessProblem(acquire->LastFrame()).toStdString();

  acquire->CapturePose();
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LastOutcome().contains("recorded as pose_0000.png")) << acquire->LastOutcome().toStdString();
  EXPECT_TRUE(acquire->Checklist()->item(0, 1)->text().contains("recorded"));
  EXPECT_TRUE(QFile::exists(dir + "/images/pose_0000.png"));
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 1);  // saved after the pose, not at the end
  EXPECT_EQ(acquire->CurrentPose(), 1);
  acquire->SkipPose();
  EXPECT_EQ(acquire->Checklist()->item(1, 1)->text(), "skipped");
  EXPECT_EQ(acquire->CurrentPose(), 2);

  acquire->RunRest();  // every pose not yet recorded, the skipped one included
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }, 120000));
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), poses);
  EXPECT_EQ(window.Session()->State(Step::kAcquire), StepState::kDone);

  // Redo by hand: a camera only, the readings typed for the pose.
  acquire->Connect("none", "file:" + dir + "/images/pose_0003.png");
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected(); }));
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(button("acquire_capture")->isEnabled());
  EXPECT_FALSE(button("acquire_move")->isEnabled());  // no controller
  EXPECT_FALSE(button("acquire_run_the_rest")->isEnabled());
  acquire->SelectPose(0);
  acquire->RedoPose();
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LastOutcome().contains("pose 1 recorded")) << acquire->LastOutcome().toStdString();
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), poses);
  const Robot& robot = window.Session()->NominalRobot();
  const LegReadings planned = InverseKinematics(robot, robot.PoseFromVector(window.Session()->Plan()[0]));
  const std::vector<LegsRow>& rows = window.Session()->Legs();
  const auto redone = std::find_if(rows.begin(), rows.end(), [](const LegsRow& r) { return r.image == "pose_0000.png"; });
  ASSERT_NE(redone, rows.end());
  EXPECT_LT((redone->legs - planned).norm(), 1e-9);  // the dialog's prefilled lengths, unattended

  window.Calibrate()->Run();
  ASSERT_TRUE(WaitFor([&] { return !window.Calibrate()->Job()->Running(); }, 120000));
  EXPECT_TRUE(window.Calibrate()->LastOutcome().startsWith("done")) << window.Calibrate()->LastOutcome().toStdString();
}

// Replanning over recorded poses (issue 35): the question keep / archive /
// discard / cancel; a capture belongs to the pose it was commanded to, so
// an old pose_0000.png is not "recorded" for a new plan's pose 1, whose
// capture then gets a free name.
TEST(UiFlow, ReplanningOverRecordedPosesKeepsArchivesOrDiscardsTheCaptures) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  QFile::remove(dir + "/legs.csv");
  StatusOr<std::vector<Vector6d>> planned = LoadPoses((sessions_dir + "/calibrated/plan.csv").toStdString());
  ASSERT_TRUE(planned.ok());
  const std::vector<Vector6d> old_plan(planned->begin(), planned->begin() + 3);
  ASSERT_TRUE(workflow::WritePlanCsv((dir + "/plan.csv").toStdString(),
                                     PlanningModel{*LoadRobot("inria-left-hand"), std::nullopt, std::nullopt}, old_plan)
                  .ok());
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  AcquirePanel* acquire = window.Acquire();
  const Robot& robot = window.Session()->NominalRobot();
  const auto ik = [&](const Vector6d& pose) { return InverseKinematics(robot, robot.PoseFromVector(pose)); };
  acquire->Connect("none", "file:" + sessions_dir + "/rendered/view_0000.png");
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected() && !acquire->Job()->Running(); }));
  const auto capture = [&](int pose) {
    acquire->SelectPose(pose);
    acquire->CapturePose(ik(window.Session()->Plan()[pose]));
    return WaitFor([&] { return !acquire->Job()->Running(); });
  };
  ASSERT_TRUE(capture(0));
  ASSERT_TRUE(capture(1));
  const auto state = [&](int pose) { return acquire->Checklist()->item(pose, 1)->text(); };
  EXPECT_EQ(state(0), "✓ recorded");
  EXPECT_EQ(state(1), "✓ recorded");
  EXPECT_EQ(state(2), "to do");

  QStringList asked;
  int answer = 3;  // Cancel
  SetChoiceAnswerer([&](const QString&, const QString& text, const QStringList& choices) {
    asked << text;
    EXPECT_EQ(choices, (QStringList{"Keep captures", "Archive captures", "Discard captures", "Cancel"}));
    return answer;
  });
  PlanPanel* plan = window.Plan();
  const QByteArray legs_before = ReadBytes(dir + "/legs.csv");
  // Cancel: nothing changes.
  EXPECT_FALSE(plan->ApplyPlan({old_plan[2], old_plan[1]}));
  ASSERT_EQ(asked.size(), 1);
  EXPECT_TRUE(asked.back().contains("leaves 1 recorded capture without its pose (pose_0000.png)"))
      << asked.back().toStdString();
  EXPECT_EQ(window.Session()->Plan(), old_plan);
  EXPECT_EQ(ReadBytes(dir + "/legs.csv"), legs_before);

  // Keep: the new pose 1 is to do although pose_0000.png is there; its
  // capture becomes pose_0000_2.png. The new pose 2 is the old pose 2: recorded.
  answer = 0;
  ASSERT_TRUE(plan->ApplyPlan({old_plan[2], old_plan[1]}));
  EXPECT_EQ(window.Session()->Plan().size(), 2u);
  EXPECT_TRUE(QFile::exists(dir + "/images/pose_0000.png"));
  EXPECT_EQ(state(0), "to do");
  EXPECT_EQ(state(1), "✓ recorded");
  EXPECT_EQ(acquire->ImageOfPose(0), "pose_0000_2.png");
  EXPECT_TRUE(plan->LastOutcome().contains("Kept 1 capture of the earlier plan")) << plan->LastOutcome().toStdString();
  ASSERT_TRUE(capture(0));
  EXPECT_TRUE(acquire->LastOutcome().contains("recorded as pose_0000_2.png")) << acquire->LastOutcome().toStdString();
  EXPECT_EQ(state(0), "✓ recorded");
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 3);

  // Archive: the captures at poses the plan [old pose 1] does not have move
  // out; pose_0000.png, taken at old pose 1, is its pose 1's capture again.
  answer = 1;
  ASSERT_TRUE(plan->ApplyPlan({old_plan[0]}));
  EXPECT_EQ(state(0), "✓ recorded");
  EXPECT_EQ(acquire->ImageOfPose(0), "pose_0000.png");
  EXPECT_FALSE(QFile::exists(dir + "/images/pose_0001.png"));
  EXPECT_FALSE(QFile::exists(dir + "/images/pose_0000_2.png"));
  const QStringList archives = QDir(dir + "/archive").entryList(QDir::Dirs | QDir::NoDotAndDotDot);
  ASSERT_EQ(archives.size(), 1);
  EXPECT_TRUE(QFile::exists(dir + "/archive/" + archives[0] + "/images/pose_0001.png"));
  EXPECT_TRUE(QFile::exists(dir + "/archive/" + archives[0] + "/images/pose_0000_2.png"));
  EXPECT_EQ(CsvRows(dir + "/archive/" + archives[0] + "/legs.csv"), 2);
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 1);
  EXPECT_TRUE(window.Session()->LegsError().isEmpty()) << window.Session()->LegsError().toStdString();

  // Discard: deleted with their readings.
  answer = 2;
  ASSERT_TRUE(plan->ApplyPlan({old_plan[1]}));
  EXPECT_FALSE(QFile::exists(dir + "/images/pose_0000.png"));
  EXPECT_EQ(CsvRows(dir + "/legs.csv"), 0);
  EXPECT_EQ(state(0), "to do");
  EXPECT_EQ(asked.size(), 4);
  SetChoiceAnswerer({});
}

// File > New session with a robot file that does not load (issue 35): an
// error, and no folder or session.yaml left behind, as the CLI; a retry
// with a robot that loads makes it.
TEST(UiFlow, AFailedNewSessionLeavesNothingBehind) {
  QTemporaryDir temp;
  const QString garbage = temp.filePath("garbage.yaml");
  WriteTextFile(garbage.toStdString(), "this is: [not a robot\n");
  SessionConfig config;
  config.robot = garbage.toStdString();
  config.camera = kSimulatedCameraName;
  config.target = kDefaultTargetName;
  MainWindow window;
  const QString dir = temp.filePath("new-session");
  const Status made = window.Session()->Create(dir, config);
  EXPECT_FALSE(made.ok());
  EXPECT_NE(made.message().find("garbage.yaml"), std::string::npos) << made.message();
  EXPECT_FALSE(QFileInfo::exists(dir));
  EXPECT_FALSE(window.Session()->IsOpen());
  config.camera = "no-such-camera.yaml";
  config.robot = "inria-left-hand";
  EXPECT_FALSE(window.Session()->Create(dir, config).ok());
  EXPECT_FALSE(QFileInfo::exists(dir));
  config.camera = kSimulatedCameraName;
  ASSERT_TRUE(window.Session()->Create(dir, config).ok());
  EXPECT_TRUE(QFileInfo::exists(dir + "/session.yaml"));
  EXPECT_TRUE(window.Session()->IsOpen());
}

// One number format per quantity with its unit, and the GUI's controls where
// the workflow's sentences name the CLI's flags (issue 35).
TEST(UiFlow, OneFormatPerQuantityAndTheGuisOwnTerms) {
  EXPECT_EQ(FormatCount(1, "pose"), "1 pose");
  EXPECT_EQ(FormatCount(12, "pose"), "12 poses");
  EXPECT_EQ(FormatPixelCoordinate(903.456), "903.5 px");
  EXPECT_EQ(FormatPixels(0.21449), "0.214 px");
  EXPECT_EQ(FormatSeconds(0.8234), "0.823 s");
  EXPECT_EQ(FormatSeconds(1234.4), "1234 s");
  EXPECT_EQ(FormatCoordinate(52.249612), "52.2496");
  const QStringList cli = {
      "camera 'sim' looks at the sim world: use it with --controller sim",
      "camera 'sim' renders the sim world's platform: it needs --controller sim",
      "no plan.csv: hexcal plan --out /s/plan.csv",
      "no legs.csv: acquire the planned poses (hexcal acquire) or enter the readings of each image",
      "3 images with readings, 0 held out; 3 of 8 planned poses recorded: acquire the rest (hexcal acquire resumes)",
      "4 of 8 images not measured yet (calibrate --session measures them)",
      "no results: hexcal calibrate --session /s",
      "legs.csv changed since the results: run hexcal calibrate --session again",
      "results/report.json: does not match results/manifest.json; run `hexcal calibrate --session /s/x y` again",
      "recalibrate the camera (hexcal intrinsics) or make results/camera.yaml the session's camera",
      "add poses (hexcal plan) and calibrate again",
      "plan poses with hexcal plan (IOOPS) instead of random or repeated ones",
      "see each image's status with hexcal measure --session; keep the whole board in view and sharp",
      "1 reading beyond 5σ; without --keep-outliers it is left out",
      "check that the robot file is the calibrated one and that --noise-* match the sensors; if so, calibrate",
      "pose 3: unreachable; the run stops here: look at the machine, then run hexcal acquire again to go on",
      "images/pose_0002.png exists without a row in legs.csv and hexcal acquire did not write it: move it away, "
      "or record its readings (hexcal session record), then run again",
  };
  const QRegularExpression flag("(^|\\s|\\()--[a-z]|hexcal [a-z]");
  for (const QString& message : cli) {
    const QString said = InGuiTerms(message);
    EXPECT_FALSE(said.contains(flag)) << message.toStdString() << " -> " << said.toStdString();
  }
  // The step list's sentence for a one-pose plan.
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.camera = kSimulatedCameraName;
  config.target = kDefaultTargetName;
  ASSERT_TRUE(InitSession(dir.toStdString(), config).ok());
  MainWindow window;
  ASSERT_TRUE(window.OpenSession(dir));
  auto* steps = window.findChild<QListWidget*>("step_list");
  ASSERT_NE(steps, nullptr);
  EXPECT_TRUE(steps->item(static_cast<int>(Step::kPlan))->toolTip().contains("run the planner (Plan step)"))
      << steps->item(static_cast<int>(Step::kPlan))->toolTip().toStdString();
  window.Plan()->AddPose();  // the centre of the pose box
  const QString plan_tip = steps->item(static_cast<int>(Step::kPlan))->toolTip();
  EXPECT_TRUE(plan_tip.contains("1 pose,")) << plan_tip.toStdString();
  EXPECT_FALSE(plan_tip.contains("1 poses")) << plan_tip.toStdString();
  // The pose table's coordinates to 1e-4 ("53.5000", not "53.5" beside "-18.17").
  for (int column = 1; column <= 12; ++column)
    EXPECT_TRUE(window.Plan()->PoseTable()->item(0, column)->text().contains(QRegularExpression("^-?[0-9]+\\.[0-9]{4}$")))
        << window.Plan()->PoseTable()->item(0, column)->text().toStdString();
  // An option's count unit in the right number.
  auto* removal = window.Plan()->Options()->findChild<QDoubleSpinBox*>("removal_choices");
  ASSERT_NE(removal, nullptr);
  removal->setValue(1);
  EXPECT_EQ(removal->suffix(), " pose");
  removal->setValue(2);
  EXPECT_EQ(removal->suffix(), " poses");
  // The robot's dimensions: the unit in the header, four decimals in the cells.
  auto* legs = window.Robot()->findChild<QTableWidget*>("robot_legs");
  ASSERT_NE(legs, nullptr);
  EXPECT_EQ(legs->horizontalHeaderItem(2)->text(), "offset l (cm)");
  EXPECT_TRUE(legs->item(0, 2)->text().contains(QRegularExpression("^-?[0-9]+\\.[0-9]{4}$")))
      << legs->item(0, 2)->text().toStdString();
  EXPECT_EQ(legs->item(0, 3)->text(), "0.0000 … 3.5000");
}

TEST(UiFlow, BadSessionIsAnErrorNotACrash) {
  MainWindow window;
  EXPECT_FALSE(window.OpenSession("/nonexistent/session"));
  EXPECT_FALSE(window.Session()->IsOpen());
  window.Plan()->Run();  // no session: an error message, nothing runs
  EXPECT_FALSE(window.Plan()->Job()->Running());
}

}  // namespace
}  // namespace hexcal::ui

int main(int argc, char** argv) {
  return hexcal::ui::RunGuiTests(argc, argv, "ui_flow_test", &hexcal::ui::sessions_dir);
}

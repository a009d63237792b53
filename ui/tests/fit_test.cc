// Every panel fits the screen in every state (issue 35): before and after
// each job — plan, acquire on the sim devices, measure, calibrate, validate,
// the section 8 study — with the run log open, a poor verdict, stale
// results, and long folder, image and camera names. Run under xvfb-run at
// 1024×600 and 1280×720 (ui/CMakeLists.txt); fails if the window exceeds the
// screen, a panel needs scrolling, a control is clipped or a table shows too
// few rows (gui_test_support.h, FitProblems).
// With HEXCAL_GUI_SHOTS=DIR it also writes a PNG of every state to DIR
// (docs/images/gui-PANEL-STATE.png, docs/gui.md).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QListWidget>
#include <QSurfaceFormat>
#include <QTemporaryDir>

#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/calibrate_panel.h"
#include "ui/error_dialog.h"
#include "ui/main_window.h"
#include "ui/measure_panel.h"
#include "ui/plan_options.h"
#include "ui/plan_panel.h"
#include "ui/run_log.h"
#include "ui/screenshot.h"
#include "ui/study_view.h"
#include "ui/tests/gui_test_support.h"
#include "ui/validate_panel.h"
#include "ui/verdict_view.h"
#include "vision/camera.h"

namespace hexcal::ui {
namespace {

QString sessions_dir;  // argv[1]: what make_session wrote
QString shots_dir;     // $HEXCAL_GUI_SHOTS: where the states' PNGs go, if anywhere

// A folder name no label may widen the window for.
const char* kLongFolder = "a-session-folder-whose-name-is-far-too-long-to-fit-on-one-line-of-any-label-in-the-window";

// The screenshot first: it lets the jobs a refresh started end and the
// layouts settle, so that what is checked is what the picture shows.
void ExpectFits(MainWindow* window, const char* panel, const char* state) {
  ASSERT_TRUE(window->ShowPanelNamed(panel));
  if (shots_dir.isEmpty()) {
    Settle(400);
  } else {
    EXPECT_TRUE(SaveWindowScreenshot(window, QString("%1/gui-%2-%3.png").arg(shots_dir, panel, state)));
  }
  EXPECT_EQ(FitProblems(window), std::vector<std::string>{}) << panel << ", " << state;
}

// The worst verdict there is: every finding poor, each with long advice.
workflow::Verdict PoorVerdict() {
  workflow::Verdict verdict;
  for (const char* aspect : {"held-out error", "closure", "residuals", "parameters (σ)", "parameters (change)",
                             "identifiability", "poses", "unusable images", "outliers"})
    verdict.Add({aspect, workflow::VerdictLevel::kPoor, "12.3 cm", "≤ 0.05 cm",
                 "what the figure means, in one sentence",
                 "check the robot file's unit and the camera's intrinsics, then record more poses spread over the "
                 "workspace and calibrate again"});
  return verdict;
}

// The whole job at the screen's size: every panel before anything runs, then
// after each step.
TEST(UiFit, EveryPanelFitsBeforeAndAfterEveryJob) {
  QTemporaryDir temp;
  const QString dir = temp.filePath(kLongFolder);
  ASSERT_TRUE(CopyFolder(sessions_dir + "/session", dir));
  QFile::remove(dir + "/legs.csv");
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  for (const char* panel : {"robot", "plan", "acquire", "measure", "calibrate", "validate", "study"})
    ExpectFits(&window, panel, "new");

  PlanPanel* plan = window.Plan();
  plan->Options()->SetValue("poses", 12);
  plan->Options()->SetValue("candidate_count", 300);
  plan->Options()->SetText("candidate_kind", "random");
  plan->Options()->SetValue("iterations", 20);
  plan->Run();
  ASSERT_TRUE(WaitFor([&] { return !plan->Job()->Running(); }));
  ExpectFits(&window, "plan", "planned");
  ExpectFits(&window, "robot", "planned");

  // The demo's plan, whose poses the sim camera sees, acquired on the sim devices.
  QFile::remove(dir + "/plan.csv");
  ASSERT_TRUE(QFile::copy(sessions_dir + "/calibrated/plan.csv", dir + "/plan.csv"));
  window.Session()->Reload();
  AcquirePanel* acquire = window.Acquire();
  ASSERT_TRUE(window.ShowPanelNamed("acquire"));
  acquire->Connect("sim", "sim");
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected() && !acquire->Job()->Running(); }));
  ExpectFits(&window, "acquire", "connected");
  acquire->RunRest();
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }, 180000));
  ExpectFits(&window, "acquire", "acquired");
  acquire->Disconnect();
  ExpectFits(&window, "acquire", "disconnected");  // the buttons that need devices disabled
  // A new plan over the recorded poses, the captures kept: its poses are
  // recorded by the pose each capture was commanded to, not by the name.
  const std::vector<Vector6d> acquired = window.Session()->Plan();
  Vector6d moved = acquired[0];
  moved[2] += 0.5;
  SetChoiceAnswerer([](const QString&, const QString&, const QStringList&) { return 0; });  // Keep captures
  ASSERT_TRUE(plan->ApplyPlan({moved, acquired[3], acquired[1], acquired[2]}));
  window.Acquire()->SelectPose(0);
  ExpectFits(&window, "acquire", "replanned");
  ASSERT_TRUE(plan->ApplyPlan(acquired));  // the acquired plan again, nothing left to ask about
  SetChoiceAnswerer({});

  MeasurePanel* measure = window.Measure();
  measure->MeasureAll();
  ASSERT_TRUE(WaitFor([&] { return !measure->Job()->Running(); }));
  ExpectFits(&window, "measure", "measured");

  CalibratePanel* calibrate = window.Calibrate();
  calibrate->Run();
  ASSERT_TRUE(WaitFor([&] { return !calibrate->Job()->Running(); }, 120000));
  EXPECT_TRUE(calibrate->LastOutcome().startsWith("done")) << calibrate->LastOutcome().toStdString();
  ExpectFits(&window, "calibrate", "calibrated");
  calibrate->Log()->SetExpanded(true);
  ExpectFits(&window, "calibrate", "run-log");
  ExpectFits(&window, "validate", "calibrated");

  StudyView* study = window.Validate()->Study();
  ASSERT_TRUE(window.ShowPanelNamed("study"));
  study->SetOption("select", "8");
  study->SetOption("subsets", "20");
  study->Run();
  ASSERT_TRUE(WaitFor([&] { return !study->Job()->Running(); }));
  EXPECT_TRUE(study->LastOutcome().startsWith("done")) << study->LastOutcome().toStdString();
  ExpectFits(&window, "study", "done");
}

// The calibrated session, then with an image of a long name added (no
// readings yet, results stale), a camera file of a long path, and a poor verdict.
TEST(UiFit, LongNamesStaleResultsAndAPoorVerdictFit) {
  QTemporaryDir temp;
  const QString dir = temp.filePath(kLongFolder);
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  ExpectFits(&window, "validate", "held-out");  // 4 held-out images, up to date

  const QString long_image = "an_image_whose_file_name_goes_on_and_on_without_a_single_space_to_break_it_0001.png";
  const QStringList images = QDir(dir + "/images").entryList(QDir::Files, QDir::Name);
  ASSERT_FALSE(images.isEmpty());
  ASSERT_TRUE(QFile::copy(dir + "/images/" + images.front(), dir + "/images/" + long_image));
  window.Session()->Reload();
  MeasurePanel* measure = window.Measure();
  const QList<QListWidgetItem*> found = measure->ImageList()->findItems(long_image, Qt::MatchStartsWith);
  ASSERT_EQ(found.size(), 1);
  measure->ImageList()->setCurrentItem(found.front());
  ASSERT_TRUE(WaitFor([&] { return !measure->PreviewJob()->Running(); }));
  for (const char* panel : {"robot", "plan", "measure", "calibrate", "validate", "study"})
    ExpectFits(&window, panel, "stale");

  window.Acquire()->Connect("none", "file:" + dir + "/images/" + long_image);
  ASSERT_TRUE(WaitFor([&] { return window.Acquire()->Connected() && !window.Acquire()->Job()->Running(); }));
  ExpectFits(&window, "acquire", "by-hand");
  window.Acquire()->Disconnect();

  // The results are stale here: the verdict with its stale mark, as the panels show it.
  ASSERT_FALSE(window.Session()->ResultsNote().isEmpty());
  window.Calibrate()->VerdictWidget()->Show(PoorVerdict(), window.Session()->ResultsNote());
  ExpectFits(&window, "calibrate", "poor");
  window.Validate()->VerdictWidget()->Show(PoorVerdict(), window.Session()->ResultsNote());
  ExpectFits(&window, "validate", "poor");

  // Another camera: no image is "ok" with measurements made with the old one.
  StatusOr<Camera> camera = LoadCamera(window.Session()->Resolve(window.Session()->Config().camera));
  ASSERT_TRUE(camera.ok());
  camera->fx *= 1.01;
  ASSERT_TRUE(SaveCamera(*camera, (dir + "/camera.yaml").toStdString()).ok());
  ASSERT_TRUE(ApplySessionEdit(&window, "Intrinsics",
                               [&](bool overwrite) { return window.Session()->SetCamera("camera.yaml", overwrite); }));
  ExpectFits(&window, "measure", "new-camera");
}

}  // namespace
}  // namespace hexcal::ui

int main(int argc, char** argv) {
  hexcal::ui::shots_dir = qEnvironmentVariable("HEXCAL_GUI_SHOTS");
  return hexcal::ui::RunGuiTests(argc, argv, "ui_fit_test", &hexcal::ui::sessions_dir);
}

#include "ui/main_window.h"

#include <QCloseEvent>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QMenuBar>
#include <QScreen>
#include <QSettings>
#include <QStackedWidget>
#include <QStandardPaths>
#include <QStatusBar>
#include <sstream>

#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/calibrate_panel.h"
#include "ui/error_dialog.h"
#include "ui/help_browser.h"
#include "ui/measure_panel.h"
#include "ui/new_session_dialog.h"
#include "ui/panel_scroll.h"
#include "ui/plan_panel.h"
#include "ui/robot_panel.h"
#include "ui/step_list.h"
#include "ui/validate_panel.h"
#include "workflow/demo.h"

namespace hexcal::ui {
namespace {

constexpr int kRecentSessions = 8;
const char* kRecentKey = "recent_sessions";

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), session_(new SessionState(this)), demo_job_(new BackgroundJob(this)) {
  setWindowTitle("hexcal — hexapod calibration");
  steps_ = new StepList(session_);
  stack_ = new QStackedWidget;
  robot_ = new RobotPanel(session_);
  plan_ = new PlanPanel(session_);
  acquire_ = new AcquirePanel(session_);
  measure_ = new MeasurePanel(session_);
  calibrate_ = new CalibratePanel(session_);
  validate_ = new ValidatePanel(session_);
  // Each panel in a scroll area: however much a panel holds (a long verdict,
  // a long file name), it cannot make the window larger than the screen; the
  // panels are laid out to need no scrolling at 1024×600 (ui/tests/fit_test.cc).
  for (QWidget* panel : std::initializer_list<QWidget*>{robot_, plan_, acquire_, measure_, calibrate_, validate_})
    stack_->addWidget(new PanelScroll(panel));
  connect(steps_, &QListWidget::currentRowChanged, stack_, &QStackedWidget::setCurrentIndex);
  connect(plan_, &PlanPanel::PoseSelected, robot_, &RobotPanel::ShowPlannedPose);
  connect(session_, &SessionState::Changed, this, [this] {
    setWindowTitle("hexcal — " + session_->Dir());
    // The folder elided in the middle: a long path would cut off the sentence.
    const QString dir = statusBar()->fontMetrics().elidedText(session_->Dir(), Qt::ElideMiddle, width() / 2);
    statusBar()->showMessage("session " + dir + " (every change is saved to the folder)");
  });
  auto* central = new QWidget;
  auto* layout = new QHBoxLayout(central);
  layout->addWidget(steps_);
  layout->addWidget(stack_, 1);
  setCentralWidget(central);
  BuildMenus();
  steps_->setCurrentRow(0);
  statusBar()->showMessage("Open a session (File > Open) or the demo session (File > Open demo session).");
  FitScreen(QSize(1280, 720));
}

void MainWindow::FitScreen(const QSize& wanted) {
  // 1280×720, the screen it is made for, or the screen when smaller (1024×600).
  const QRect screen = this->screen()->availableGeometry();
  resize(wanted.boundedTo(screen.size()));
  move(screen.topLeft());
}

void MainWindow::BuildMenus() {
  QMenu* file = menuBar()->addMenu("&File");
  file->addAction("&New session…", this, &MainWindow::NewSession, QKeySequence::New);
  file->addAction("&Open session…", this, &MainWindow::OpenSessionDialog, QKeySequence::Open);
  file->addAction("Open &demo session", this, &MainWindow::OpenDemoSession);
  recent_menu_ = file->addMenu("&Recent sessions");
  // No Save: every change is written to the folder as it is made.
  file->addAction("&Reload session", this, [this] { session_->Reload(); }, QKeySequence::Refresh);
  file->addSeparator();
  file->addAction("&Quit", this, &QWidget::close, QKeySequence::Quit);
  QMenu* view = menuBar()->addMenu("&View");
  for (int k = 0; k < kNumSteps; ++k)
    view->addAction(
        StepName(static_cast<Step>(k)), this, [this, k] { ShowStep(static_cast<Step>(k)); },
        QKeySequence(Qt::CTRL + Qt::Key_1 + k));
  AddHelpMenu(menuBar(), this);
  FillRecentMenu();
}

bool MainWindow::OpenSession(const QString& dir) {
  const Status opened = session_->Open(dir);
  if (!opened.ok()) {
    ShowError(this, "Open session",
              QString::fromStdString(opened.message()) +
                  "\nA session folder holds session.yaml (hexcal session init, or File > New).");
    return false;
  }
  RememberRecent(session_->Dir());
  return true;
}

void MainWindow::ShowStep(Step step) { steps_->setCurrentRow(static_cast<int>(step)); }

bool MainWindow::ShowPanelNamed(const QString& name) {
  // "study": the Validate step's section 8 study tab.
  if (name.compare("study", Qt::CaseInsensitive) == 0) {
    ShowStep(Step::kValidate);
    validate_->ShowStudyTab();
    return true;
  }
  if (name.compare("validate", Qt::CaseInsensitive) == 0) validate_->ShowValidationTab();
  for (int k = 0; k < kNumSteps; ++k)
    if (name.compare(StepName(static_cast<Step>(k)), Qt::CaseInsensitive) == 0) {
      ShowStep(static_cast<Step>(k));
      return true;
    }
  return false;
}

void MainWindow::NewSession() {
  NewSessionDialog dialog(this);
  if (dialog.exec() != QDialog::Accepted) return;
  const Status made = session_->Create(dialog.Folder(), dialog.Config());
  if (!made.ok()) return ShowError(this, "New session", QString::fromStdString(made.message()));
  RememberRecent(session_->Dir());
  ShowStep(Step::kPlan);
}

void MainWindow::OpenSessionDialog() {
  const QString dir = QFileDialog::getExistingDirectory(this, "Open session folder");
  if (!dir.isEmpty()) OpenSession(dir);
}

// `hexcal demo --out DIR`: a virtual robot and camera, planned, recorded and
// calibrated; a few tens of seconds, on a worker.
void MainWindow::OpenDemoSession() {
  const QString dir = QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).filePath("demo-session");
  if (QFileInfo::exists(dir + "/session.yaml")) {
    OpenSession(dir);
    return;
  }
  QDir().mkpath(QFileInfo(dir).path());
  statusBar()->showMessage("making the demo session in " + dir + " (hexcal demo)…");
  demo_job_->Start("demo", [this, dir](const JobContext& context) -> GuiContinuation {
    workflow::DemoRequest request;
    request.out = dir.toStdString();
    request.force = true;
    const StatusOr<workflow::DemoResult> demo = workflow::RunDemo(request, JobHooks{context.progress, context.cancel});
    const Status status = demo.ok() ? Status::Ok() : demo.status();
    return [this, dir, status] {
      if (!status.ok()) {
        statusBar()->showMessage("The demo session could not be made.");  // not "making…" after the job
        return ShowError(this, "Demo session", "The demo session could not be made: " +
                                                   QString::fromStdString(status.message()));
      }
      OpenSession(dir);
    };
  });
}

void MainWindow::RememberRecent(const QString& dir) {
  if (!Interactive()) return;  // --screenshot and tests leave the operator's list alone
  QSettings settings("hexcal", "hexcal-gui");
  QStringList recent = settings.value(kRecentKey).toStringList();
  recent.removeAll(dir);
  recent.prepend(dir);
  while (recent.size() > kRecentSessions) recent.removeLast();
  settings.setValue(kRecentKey, recent);
  FillRecentMenu();
}

void MainWindow::FillRecentMenu() {
  recent_menu_->clear();
  const QStringList recent = QSettings("hexcal", "hexcal-gui").value(kRecentKey).toStringList();
  for (const QString& dir : recent) recent_menu_->addAction(dir, this, [this, dir] { OpenSession(dir); });
  recent_menu_->setEnabled(!recent.isEmpty());
}

// Back from a terminal or an editor: what the watcher may have missed (a
// network file system) is read now, if any file's stamp changed.
void MainWindow::changeEvent(QEvent* event) {
  QMainWindow::changeEvent(event);
  if (event->type() == QEvent::ActivationChange && isActiveWindow()) session_->ReloadIfChanged();
}

void MainWindow::closeEvent(QCloseEvent* event) {
  // Nothing to write: every change went to the folder when it was made, and
  // writing copies back now would undo what other programs wrote meanwhile.
  event->accept();
}

}  // namespace hexcal::ui

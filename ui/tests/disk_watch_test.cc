// The GUI notices every change on disk (issue 40): another program changes a
// file the session's status depends on — session.yaml, the robot file outside
// the session folder, camera.yaml, target.yaml, plan.csv, legs.csv,
// camera_poses.csv, an image, results/, study/ — by writing it in place (cp
// over it), replacing it (mv), deleting it, making it again, or saving it as
// editors do, through a temporary file. Within 2 s and without F5 the step
// list shows what `hexcal session status --json` says (workflow::ToJson of
// workflow::ReadSessionStatus, what the command prints), and so do the panels'
// lines: the Calibrate line, the Validate verdict's stale mark, the Measure
// step's legs.csv error, the Acquire step's plan line, the study's line.
// Where the watcher sees nothing (a network file system), the window's focus
// and the export buttons re-read the session; export and report of stale
// results ask first. Run under xvfb-run (ui/CMakeLists.txt).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QListWidget>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/robot_io.h"
#include "core/session.h"
#include "session/session_study.h"
#include "ui/acquire_panel.h"
#include "ui/calibrate_panel.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/main_window.h"
#include "ui/measure_panel.h"
#include "ui/study_view.h"
#include "ui/tests/gui_test_support.h"
#include "ui/validate_panel.h"
#include "ui/verdict_view.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/session_calibrate.h"
#include "workflow/session_status.h"
#include "workflow/study_step.h"

namespace hexcal::ui {
namespace {

QString sessions_dir;  // argv[1]: what make_session wrote
constexpr int kNoticeMs = 2000;

void Shell(const QString& program, const QStringList& args) {
  ASSERT_EQ(QProcess::execute(program, args), 0) << program.toStdString() << " " << args.join(' ').toStdString();
}

void Write(const QString& path, const QByteArray& bytes) {
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly | QIODevice::Truncate)) << path.toStdString();
  ASSERT_EQ(file.write(bytes), bytes.size());
}

// `bytes` added at the end of the file, written in place (the same inode).
void Append(const QString& path, const QByteArray& bytes) { Write(path, ReadBytes(path) + bytes); }

// What `hexcal session status --json DIR` prints (app/commands/session_command.cc),
// or {"error": message} when it fails.
nlohmann::json StatusJson(const QString& dir) {
  StatusOr<workflow::SessionStatus> status = workflow::ReadSessionStatus(dir.toStdString());
  if (!status.ok()) return {{"error", status.status().message()}};
  return workflow::ToJson(*status);
}

QString Plain(QString text) { return text.remove(QChar(0x200B)); }  // Breakable's zero-width spaces

QString LabelText(const QWidget* root, const char* name) {
  const auto* label = root->findChild<QLabel*>(name);
  return label ? Plain(label->text()) : QString("(no label %1)").arg(name);
}

// The prepared session: calibrated and studied, its robot a file outside
// the folder (../robots/robot.yaml), its camera and target files inside; the
// other versions of each file beside it in `spare/`.
class Prepared {
 public:
  static Prepared& Get() {
    static Prepared prepared;
    return prepared;
  }
  QString Root() const { return temp_.path(); }
  // The prepared folders (session, robots, spare) copied into `root`: each
  // test changes a copy of its own.
  Status CopyTo(const QString& root) const {
    if (!status.ok()) return status;
    for (const char* folder : {"session", "robots", "spare"})
      if (!CopyFolder(Root() + "/" + folder, root + "/" + folder))
        return Status::BadInput("copy " + std::string(folder));
    return Status::Ok();
  }
  Status status = Status::Ok();

 private:
  Prepared() { status = Prepare(); }
  Status Prepare() {
    const QString root = temp_.path();
    const std::string dir = (root + "/session").toStdString();
    const std::string spare = (root + "/spare").toStdString();
    const auto fail = [&](const std::string& what) { return Status::BadInput("prepare: " + what); };
    if (!CopyFolder(sessions_dir + "/calibrated", root + "/session")) return fail("copy");
    QDir().mkpath(root + "/robots");
    QDir().mkpath(root + "/spare");
    Robot robot = *LoadRobot("inria-left-hand");
    Camera camera = *LoadCamera(kSimulatedCameraName);
    const Target target = *LoadTarget(kDefaultTargetName);
    if (!SaveRobot(robot, (root + "/robots/robot.yaml").toStdString()).ok() ||
        !SaveRobot(robot, spare + "/robot.yaml").ok() || !SaveCamera(camera, dir + "/camera.yaml").ok() ||
        !SaveCamera(camera, spare + "/camera.yaml").ok())
      return fail("write robot, camera");
    robot.legs[0].offset += 0.05;  // another robot: leg 1 0.05 cm longer
    camera.fx = camera.fy = 950;   // another camera: f 950 px instead of 903
    if (!SaveRobot(robot, spare + "/robot_other.yaml").ok() || !SaveCamera(camera, spare + "/camera_950.yaml").ok())
      return fail("write the other robot, camera");
    QFile target_file(QString::fromStdString(dir + "/target.yaml"));
    const std::string target_text = TargetToYaml(target);
    if (!target_file.open(QIODevice::WriteOnly) ||
        target_file.write(target_text.data(), target_text.size()) != static_cast<qint64>(target_text.size()))
      return fail("write target");
    target_file.close();
    StatusOr<SessionConfig> config = LoadSessionConfig(dir);
    if (!config.ok()) return fail(config.status().message());
    config->robot = "../robots/robot.yaml";
    config->camera = "camera.yaml";
    config->target = "target.yaml";
    if (!SaveSessionConfig(dir, *config).ok()) return fail("session.yaml");
    StatusOr<workflow::CalibrationReport> calibrated = workflow::CalibrateSession({dir});
    if (!calibrated.ok()) return fail(calibrated.status().message());
    workflow::StudyRequest study;
    study.session = dir;
    study.study.select = 8;
    study.study.subsets = 5;
    StatusOr<workflow::StudyOutcome> studied = workflow::RunStudy(study);
    if (!studied.ok()) return fail(studied.status().message());
    // The files as they are now, to put back.
    for (const char* name : {"session.yaml", "legs.csv", "plan.csv", "camera_poses.csv", "target.yaml"})
      QFile::copy(QString::fromStdString(dir) + "/" + name, QString::fromStdString(spare) + "/" + name);
    QFile::copy(QString::fromStdString(dir) + "/images/view_0000.png",
                QString::fromStdString(spare) + "/view_0000.png");
    QFile::copy(QString::fromStdString(dir) + "/results/report.json", QString::fromStdString(spare) + "/report.json");
    CopyFolder(QString::fromStdString(dir) + "/study", QString::fromStdString(spare) + "/study");
    return Status::Ok();
  }
  QTemporaryDir temp_;
};

const char* const kGuiSteps[] = {"robot", "plan", "readings", "measure", "calibrate", "validate"};

// What the study line must say of study/ as it is: "none", "stale", "current" or "broken".
QString StudyState(const QString& dir) {
  const std::string d = dir.toStdString();
  if (!workflow::HasSessionStudy(d)) return "none";
  StatusOr<workflow::SessionStudy> study = workflow::LoadSessionStudy(d);
  return !study.ok() ? "broken" : study->Stale() ? "stale" : "current";
}

// Why the window does not show what the status JSON and the study say; empty when it does.
QString Mismatch(MainWindow* window, const nlohmann::json& status, const QString& study) {
  QStringList problems;
  const auto* steps = window->findChild<QListWidget*>("step_list");
  for (int k = 0; k < 6; ++k) {
    const QListWidgetItem* row = steps->item(k);
    const QString shown_state =
        QString::fromStdString(workflow::StepStatusName(static_cast<StepState>(row->data(Qt::UserRole).toInt())));
    const QString tooltip = row->toolTip();
    if (status.contains("error")) {
      const QString error = QString::fromStdString(status["error"].get<std::string>());
      if (shown_state != "broken" || !tooltip.contains(InGuiTerms(error)))
        problems << QString("%1 shows %2 (%3), the status fails: %4").arg(kGuiSteps[k], shown_state, tooltip, error);
      continue;
    }
    const QString state = QString::fromStdString(status["steps"][kGuiSteps[k]].get<std::string>());
    // The status's sentence as the GUI words it (its controls for the CLI's flags, ui/gui_terms.h).
    const QString why = InGuiTerms(QString::fromStdString(status["why"][kGuiSteps[k]].get<std::string>()));
    if (shown_state != state || !tooltip.endsWith(why))
      problems
          << QString("%1 shows %2 '%3', the status says %4 '%5'").arg(kGuiSteps[k], shown_state, tooltip, state, why);
  }
  const auto step = [&](const char* name) {
    return status.contains("steps") ? QString::fromStdString(status["steps"][name].get<std::string>()) : QString();
  };
  const auto why = [&](const char* name) {
    return status.contains("why") ? InGuiTerms(QString::fromStdString(status["why"][name].get<std::string>()))
                                  : QString();
  };
  // The Calibrate line between runs.
  const QString calibrate = LabelText(window->Calibrate(), "calibrate_status");
  if ((step("calibrate") == "done") != (calibrate == "Results up to date with the session's files."))
    problems << "Calibrate line '" + calibrate + "', the step is " + step("calibrate");
  if (step("calibrate") == "stale" && !calibrate.contains(why("calibrate")))
    problems << "Calibrate line '" + calibrate + "' without the reason '" + why("calibrate") + "'";
  if ((status.contains("error") || step("calibrate") == "broken") && !calibrate.startsWith("Results do not load"))
    problems << "Calibrate line '" + calibrate + "', the results do not load";
  // No verdict without its stale mark, on either panel.
  for (QWidget* panel : {static_cast<QWidget*>(window->Calibrate()), static_cast<QWidget*>(window->Validate())}) {
    const QString level = LabelText(panel, "verdict_level"), findings = LabelText(panel, "verdict_findings");
    const bool stale_mark = findings.contains("Stale");
    if (!level.isEmpty() && step("calibrate") == "stale" && !stale_mark)
      problems << QString("%1 shows '%2' with no stale mark, the results are stale")
                      .arg(panel->metaObject()->className(), level);
    if (stale_mark && step("calibrate") != "stale")
      problems << QString("%1 marks its verdict stale, the results are %2")
                      .arg(panel->metaObject()->className(), step("calibrate"));
  }
  // The Measure step's legs.csv error while, and only while, it holds.
  const QString measure = LabelText(window->Measure(), "measure_status");
  const bool parse_error_shown = measure.contains(QRegularExpression("legs\\.csv:\\d+:"));
  if (parse_error_shown != (step("readings") == "broken"))
    problems << "Measure line '" + measure + "', readings " + step("readings");
  // The Acquire step's plan line.
  const QString acquire = LabelText(window->Acquire(), "acquire_status");
  const int poses = window->Acquire()->Checklist()->rowCount();
  if (acquire.contains("No plan yet") && (poses > 0 || step("plan") != "todo"))
    problems << QString("Acquire says '%1' with %2 poses listed, plan %3").arg(acquire).arg(poses).arg(step("plan"));
  if (step("plan") == "todo" && !acquire.contains("No plan yet"))
    problems << "Acquire line '" + acquire + "' with no plan";
  // The study as study/ holds it now.
  const QString rank = Plain(window->Validate()->Study()->RankLine()->text());
  if (!status.contains("error")) {
    const bool shown = rank.contains("validates better than"), stale = rank.contains("Stale");
    if ((study == "none") != rank.contains("No section 8 study yet") || (study == "current") != (shown && !stale) ||
        (study == "stale") != (shown && stale))
      problems << "study line '" + rank + "', the study is " + study;
  }
  return problems.join("\n");
}

// One line of the table in docs/gui.md: the step marks as shown.
QString Marks(MainWindow* window) {
  const auto* steps = window->findChild<QListWidget*>("step_list");
  QStringList marks;
  for (int k = 0; k < 6; ++k) marks << steps->item(k)->text().section(' ', 0, 0);
  return marks.join("");
}

struct Change {
  const char* what;
  std::function<void(const QString& root, const QString& dir)> apply;
  bool in_status = true;  // false: study/, which the status leaves out (the study's line shows it)
};

// Each change in turn on one open window: the status must change with it
// (else the check says nothing), and the window must follow within 2 s.
void WalkChanges(const std::vector<Change>& changes) {
  QTemporaryDir temp;
  const QString root = temp.path();
  const Status copied = Prepared::Get().CopyTo(root);
  ASSERT_TRUE(copied.ok()) << copied.message();
  const QString dir = root + "/session";
  const nlohmann::json initial = StatusJson(dir);
  for (const char* step : kGuiSteps) ASSERT_EQ(initial["steps"][step], "done") << initial.dump(1);
  MainWindow window;  // not shown: the texts are checked, and nothing is drawn (faster under llvmpipe)
  ASSERT_TRUE(window.OpenSession(dir));
  ASSERT_EQ(Mismatch(&window, initial, StudyState(dir)).toStdString(), "");
  nlohmann::json before = initial;
  for (const Change& change : changes) {
    Settle(20);
    const QString marks_before = Marks(&window);
    change.apply(root, dir);
    if (::testing::Test::HasFatalFailure()) return;
    const nlohmann::json after = StatusJson(dir);
    const QString study = StudyState(dir);
    if (change.in_status) {
      EXPECT_NE(after, before) << change.what << ": the status did not change";
    }
    QElapsedTimer clock;
    clock.start();
    const bool followed = WaitFor([&] { return Mismatch(&window, after, study).isEmpty(); }, kNoticeMs);
    const qint64 ms = clock.elapsed();
    EXPECT_TRUE(followed) << change.what << ":\n" << Mismatch(&window, after, study).toStdString();
    std::printf("| %s | %s → %s | %s |\n", change.what, marks_before.toUtf8().constData(),
                Marks(&window).toUtf8().constData(),
                followed ? QString("%1 ms").arg(ms).toUtf8().constData() : "not after 2 s");
    before = after;
  }
  // Reading the session writes nothing that the watch would see again: no
  // reload loop (after the last change's own reloads, 150 ms after its last event).
  Settle(300);
  int reloads = 0;
  const QMetaObject::Connection counting =
      QObject::connect(window.Session(), &SessionState::Changed, [&reloads] { ++reloads; });
  Settle(400);
  QObject::disconnect(counting);
  EXPECT_EQ(reloads, 0);
}

QString Spare(const QString& root, const char* name) { return root + "/spare/" + name; }

// cp over the file: the same inode, written in place.
void CopyOver(const QString& from, const QString& to) { Shell("cp", {from, to}); }
// mv: another inode renamed over the name.
void MoveOver(const QString& root, const QString& from, const QString& to) {
  const QString staged = root + "/staged";
  Shell("cp", {from, staged});
  Shell("mv", {staged, to});
}
// vim's save (backupcopy=no): the file renamed to FILE~, the new text written
// to FILE, the backup deleted.
void VimSave(const QString& from, const QString& to) {
  ASSERT_TRUE(QFile::rename(to, to + "~"));
  Write(to, ReadBytes(from));
  ASSERT_TRUE(QFile::remove(to + "~"));
}
// gedit's save: the text written to a hidden temporary beside it, renamed over it.
void GeditSave(const QString& from, const QString& to) {
  const QString temporary = QFileInfo(to).dir().filePath(".goutputstream-X1Y2Z3");
  Write(temporary, ReadBytes(from));
  Shell("mv", {temporary, to});
}

TEST(UiDiskWatch, CameraInTheSession) {
  WalkChanges({
      {"camera.yaml: cp of another camera (f 950 px) over it",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "camera_950.yaml"), dir + "/camera.yaml"); }},
      {"camera.yaml: cp of the first camera over it again",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "camera.yaml"), dir + "/camera.yaml"); }},
      {"camera.yaml: deleted",
       [](const QString&, const QString& dir) { ASSERT_TRUE(QFile::remove(dir + "/camera.yaml")); }},
      {"camera.yaml: made again (the first camera)",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "camera.yaml"), dir + "/camera.yaml"); }},
      {"camera.yaml: mv of another camera over it",
       [](const QString& root, const QString& dir) {
         MoveOver(root, Spare(root, "camera_950.yaml"), dir + "/camera.yaml");
       }},
      {"camera.yaml: saved by an editor through a backup (vim)",
       [](const QString& root, const QString& dir) { VimSave(Spare(root, "camera.yaml"), dir + "/camera.yaml"); }},
      {"camera.yaml: saved by an editor through a temporary (gedit)",
       [](const QString& root, const QString& dir) {
         GeditSave(Spare(root, "camera_950.yaml"), dir + "/camera.yaml");
       }},
      {"camera.yaml: cp over it after those renames",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "camera.yaml"), dir + "/camera.yaml"); }},
  });
}

TEST(UiDiskWatch, RobotOutsideTheSession) {
  WalkChanges({
      {"../robots/robot.yaml: cp of another robot over it",
       [](const QString& root, const QString&) {
         CopyOver(Spare(root, "robot_other.yaml"), root + "/robots/robot.yaml");
       }},
      {"../robots/robot.yaml: mv of the first robot over it",
       [](const QString& root, const QString&) {
         MoveOver(root, Spare(root, "robot.yaml"), root + "/robots/robot.yaml");
       }},
      {"../robots/robot.yaml: deleted",
       [](const QString& root, const QString&) { ASSERT_TRUE(QFile::remove(root + "/robots/robot.yaml")); }},
      {"../robots/robot.yaml: made again (the first robot)",
       [](const QString& root, const QString&) { CopyOver(Spare(root, "robot.yaml"), root + "/robots/robot.yaml"); }},
      {"../robots/robot.yaml: saved by an editor through a temporary",
       [](const QString& root, const QString&) {
         GeditSave(Spare(root, "robot_other.yaml"), root + "/robots/robot.yaml");
       }},
      {"../robots/robot.yaml: cp over it after the rename",
       [](const QString& root, const QString&) { CopyOver(Spare(root, "robot.yaml"), root + "/robots/robot.yaml"); }},
  });
}

TEST(UiDiskWatch, SessionFiles) {
  WalkChanges({
      {"target.yaml: written in place (tags 2 % larger)",
       [](const QString&, const QString& dir) {
         QByteArray text = ReadBytes(dir + "/target.yaml");
         const QRegularExpressionMatch size = QRegularExpression("tag_size: ([0-9.e-]+)").match(QString(text));
         ASSERT_TRUE(size.hasMatch()) << text.toStdString();
         text.replace(size.captured(0).toUtf8(),
                      ("tag_size: " + QString::number(size.captured(1).toDouble() * 1.02, 'g', 12)).toUtf8());
         Write(dir + "/target.yaml", text);
       }},
      {"target.yaml: the first one back, in place",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "target.yaml"), dir + "/target.yaml"); }},
      {"session.yaml: written in place (another leg noise)",
       [](const QString&, const QString& dir) {
         QByteArray text = ReadBytes(dir + "/session.yaml");
         ASSERT_TRUE(text.contains("  leg: 0.001"));
         Write(dir + "/session.yaml", text.replace("  leg: 0.001", "  leg: 0.002"));
       }},
      {"session.yaml: deleted",
       [](const QString&, const QString& dir) { ASSERT_TRUE(QFile::remove(dir + "/session.yaml")); }},
      {"session.yaml: made again (the first one)",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "session.yaml"), dir + "/session.yaml"); }},
      {"legs.csv: a line of 2 columns appended in place",
       [](const QString&, const QString& dir) { Append(dir + "/legs.csv", "view_0099.png,1.5\n"); }},
      {"legs.csv: fixed in place",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "legs.csv"), dir + "/legs.csv"); }},
      {"plan.csv: deleted", [](const QString&, const QString& dir) { ASSERT_TRUE(QFile::remove(dir + "/plan.csv")); }},
      {"plan.csv: made again",
       [](const QString& root, const QString& dir) { CopyOver(Spare(root, "plan.csv"), dir + "/plan.csv"); }},
      {"plan.csv: a bad number written in place",
       [](const QString&, const QString& dir) { Append(dir + "/plan.csv", "1,2,3,4,five,6\n"); }},
      {"plan.csv: fixed by an editor through a temporary",
       [](const QString& root, const QString& dir) { GeditSave(Spare(root, "plan.csv"), dir + "/plan.csv"); }},
      {"images/view_0000.png: cp of another image over it",
       [](const QString&, const QString& dir) {
         CopyOver(dir + "/images/view_0001.png", dir + "/images/view_0000.png");
       }},
      {"images/view_0000.png: the first image back, in place",
       [](const QString& root, const QString& dir) {
         CopyOver(Spare(root, "view_0000.png"), dir + "/images/view_0000.png");
       }},
      {"camera_poses.csv: a row deleted in place",
       [](const QString&, const QString& dir) {
         QList<QByteArray> lines = ReadBytes(dir + "/camera_poses.csv").split('\n');
         ASSERT_GT(lines.size(), 3);
         lines.removeAt(2);
         Write(dir + "/camera_poses.csv", lines.join('\n'));
       }},
      {"camera_poses.csv: the first one back, in place",
       [](const QString& root, const QString& dir) {
         CopyOver(Spare(root, "camera_poses.csv"), dir + "/camera_poses.csv");
       }},
      {"results/report.json: written in place",
       [](const QString&, const QString& dir) { Append(dir + "/results/report.json", " "); }},
      {"results/report.json: the first one back, in place",
       [](const QString& root, const QString& dir) {
         CopyOver(Spare(root, "report.json"), dir + "/results/report.json");
       }},
      {"study/: deleted (rm -r)",
       [](const QString&, const QString& dir) {
         Shell("rm", {"-r", dir + "/study"});
       },
       false},
      {"study/: put back (cp -r)",
       [](const QString& root, const QString& dir) {
         Shell("cp", {"-r", Spare(root, "study"), dir + "/study"});
       },
       false},
  });
}

// Where the watcher sees nothing (here: turned off, as on a network file
// system), the window reads the session again when it gains focus, and
// before calibrating or exporting; export and report of results stale since
// an in-place camera change ask first, with the reason, and act only on yes.
TEST(UiDiskWatch, FocusAndActionsReadAgainStaleExportAsks) {
  QTemporaryDir temp;
  const QString root = temp.path();
  const Status copied = Prepared::Get().CopyTo(root);
  ASSERT_TRUE(copied.ok()) << copied.message();
  const QString dir = root + "/session";
  MainWindow window;
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  window.Session()->SetWatcherEnabled(false);
  EXPECT_TRUE(window.Session()->WatchedPaths().isEmpty());
  const auto refocus = [&] {
    QApplication::setActiveWindow(nullptr);
    QApplication::setActiveWindow(&window);
    QApplication::processEvents();
  };
  refocus();

  // Unseen until the window gains focus.
  CopyOver(Spare(root, "camera_950.yaml"), dir + "/camera.yaml");
  Settle(500);  // more than the watcher's 150 ms and a reload
  EXPECT_EQ(Marks(&window), "✓✓✓✓✓✓");
  refocus();
  nlohmann::json status = StatusJson(dir);
  EXPECT_EQ(status["steps"]["calibrate"], "stale");
  EXPECT_EQ(Mismatch(&window, status, StudyState(dir)).toStdString(), "");

  // Export: the session read again first, then a question with the reason.
  CopyOver(Spare(root, "camera.yaml"), dir + "/camera.yaml");  // unseen: the window still says stale
  std::vector<QString> asked;
  bool answer = false;
  SetStaleAnswerer([&](const QString& what, const QString& reason) {
    asked.push_back(what + ": " + reason);
    return answer;
  });
  const QString robot_out = root + "/exported.yaml", report_out = root + "/report.html";
  window.Validate()->ExportCalibratedRobot(robot_out);
  EXPECT_TRUE(asked.empty()) << asked.front().toStdString();  // up to date on disk: no question
  EXPECT_EQ(ReadBytes(robot_out), ReadBytes(dir + "/results/calibrated.yaml"));
  ASSERT_TRUE(QFile::remove(robot_out));

  CopyOver(Spare(root, "camera_950.yaml"), dir + "/camera.yaml");  // unseen: the window says up to date
  EXPECT_EQ(Marks(&window), "✓✓✓✓✓✓");
  window.Validate()->ExportCalibratedRobot(robot_out);
  window.Validate()->ExportHtmlReport(report_out);
  ASSERT_EQ(asked.size(), 2u);
  for (const QString& question : asked)
    EXPECT_TRUE(question.contains("camera camera.yaml changed since the results")) << question.toStdString();
  EXPECT_TRUE(asked[0].startsWith("Export robot")) << asked[0].toStdString();
  EXPECT_TRUE(asked[1].startsWith("Export report")) << asked[1].toStdString();
  EXPECT_FALSE(QFile::exists(robot_out));  // refused: Cancel
  EXPECT_FALSE(QFile::exists(report_out));
  EXPECT_EQ(Mismatch(&window, StatusJson(dir), StudyState(dir)).toStdString(), "");  // the step list says why
  answer = true;                                                                     // "Use the stale results"
  window.Validate()->ExportCalibratedRobot(robot_out);
  window.Validate()->ExportHtmlReport(report_out);
  EXPECT_EQ(asked.size(), 4u);
  EXPECT_EQ(ReadBytes(robot_out), ReadBytes(dir + "/results/calibrated.yaml"));
  EXPECT_TRUE(ReadBytes(report_out).contains("Stale results."));
  SetStaleAnswerer({});

  // Not interactive, no answer set: refused.
  ASSERT_TRUE(QFile::remove(robot_out));
  window.Validate()->ExportCalibratedRobot(robot_out);
  EXPECT_FALSE(QFile::exists(robot_out));

  // Calibrate reads the session again before its checks: a legs.csv broken
  // unseen is refused by name, and nothing runs.
  Append(dir + "/legs.csv", "view_0099.png,1.5\n");
  window.Calibrate()->Run();
  EXPECT_FALSE(window.Calibrate()->Job()->Running());
  status = StatusJson(dir);
  EXPECT_EQ(status["steps"]["readings"], "broken");
  EXPECT_EQ(Mismatch(&window, status, StudyState(dir)).toStdString(), "");

  // The watcher on again: the next change is seen without focus.
  window.Session()->SetWatcherEnabled(true);
  EXPECT_TRUE(window.Session()->WatchedPaths().contains(root + "/robots/robot.yaml"));
  EXPECT_TRUE(window.Session()->WatchedPaths().contains(root + "/robots"));
  CopyOver(Spare(root, "legs.csv"), dir + "/legs.csv");
  status = StatusJson(dir);
  EXPECT_TRUE(WaitFor([&] { return Mismatch(&window, status, StudyState(dir)).isEmpty(); }, kNoticeMs))
      << Mismatch(&window, status, StudyState(dir)).toStdString();
}

}  // namespace
}  // namespace hexcal::ui

int main(int argc, char** argv) {
  return hexcal::ui::RunGuiTests(argc, argv, "ui_disk_watch_test", &hexcal::ui::sessions_dir);
}

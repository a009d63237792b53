// A points session in the GUI (issue 38; docs/session.md, "Points
// sessions"): a laser tracker's points instead of the camera's images. The
// Measure step lists every legs.csv pose with the fit of its points and the
// readings table is keyed by `pose`; a pose whose points break on disk shows
// bad_points without F5; the Calibrate step gives a verdict, its summary in
// poses and the tracker's words; New session makes a points session.
// Part of ui_readings_edit_test (ui/CMakeLists.txt), under xvfb-run.
#include <gtest/gtest.h>

#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QTemporaryDir>

#include "core/csv.h"
#include "ui/calibrate_panel.h"
#include "ui/image_view.h"
#include "ui/main_window.h"
#include "ui/measure_panel.h"
#include "ui/new_session_dialog.h"
#include "ui/readings_editor.h"
#include "ui/tests/gui_test_support.h"
#include "ui/verdict_view.h"

namespace hexcal::ui {

extern QString sessions_dir;  // readings_edit_test.cc: argv[1], what make_session wrote

namespace {

constexpr int kNoticeMs = 2000;  // the disk watch's promise (issue 40)

// points.txt without the lines of `pose`'s reflectors R3 and R4, written in
// place (the inode kept: only the file's own watch sees it).
void KeepTwoPointsOf(const QString& file, const QString& pose) {
  QFile points(file);
  ASSERT_TRUE(points.open(QIODevice::ReadOnly));
  QStringList kept;
  for (const QString& line : QString::fromUtf8(points.readAll()).split('\n'))
    if (!line.startsWith("tracker " + pose + " R3 ") && !line.startsWith("tracker " + pose + " R4 ")) kept << line;
  points.close();
  ASSERT_TRUE(points.open(QIODevice::WriteOnly | QIODevice::Truncate));
  points.write(kept.join('\n').toUtf8());
}

class PointsSessionTest : public SessionCopyTest {
 protected:
  void SetUp() override {
    ASSERT_TRUE(CopySession(sessions_dir + "/points", "points"));
    ASSERT_TRUE(OpenCopy());
    ASSERT_TRUE(window_.Session()->IsPointsSession());
  }
};

TEST_F(PointsSessionTest, MeasureListsEveryPoseAndItsFitAndTheTableIsKeyedByPose) {
  ASSERT_TRUE(window_.ShowPanelNamed("measure"));
  MeasurePanel* measure = window_.Measure();
  const std::vector<LegsRow>& legs = window_.Session()->Legs();
  ASSERT_EQ(legs.size(), 16u);
  QListWidget* poses = measure->ImageList();
  ASSERT_EQ(poses->count(), 16);
  for (int r = 0; r < poses->count(); ++r)
    EXPECT_TRUE(poses->item(r)->text().startsWith(QString::fromStdString(legs[r].image) + "  —  ok, RMS "))
        << poses->item(r)->text().toStdString();
  const QString summary = measure->PointsSummary().remove(QChar(0x200B));
  EXPECT_TRUE(summary.contains("Points: points.txt")) << summary.toStdString();
  EXPECT_TRUE(summary.contains("Reflectors: 4, from reflectors.csv. 16 of 16 poses fitted.")) << summary.toStdString();
  EXPECT_FALSE(measure->Picture()->isVisible());  // no images in a points session
  ReadingsEditor* table = measure->LegsTable();
  EXPECT_EQ(table->horizontalHeaderItem(0)->text(), "pose");
  ASSERT_EQ(table->rowCount(), 16);
  for (int r = 0; r < table->rowCount(); ++r) EXPECT_EQ(table->item(r, 0)->text().toStdString(), legs[r].image);
  EXPECT_EQ(table->MissingRows(), 0);

  // A typed reading goes into the pose's row of legs.csv, its `pose` column kept.
  const double typed = legs[1].legs[2] + 0.001;
  table->item(1, 3)->setText(QString::number(typed, 'f', 4));
  StatusOr<CsvTable> written = ReadCsv((dir_ + "/legs.csv").toStdString());
  ASSERT_TRUE(written.ok());
  EXPECT_EQ(written->header.front(), "pose");
  EXPECT_EQ(written->rows[1][0], legs[1].image);
  EXPECT_NEAR(*ParseNumber(written->rows[1][3]), QString::number(typed, 'f', 4).toDouble(), 1e-9);

  // Another program leaves pose_0002 with two points: it goes bad_points, by the watch.
  EXPECT_TRUE(window_.Session()->WatchedPaths().contains(dir_ + "/points.txt"));
  EXPECT_TRUE(window_.Session()->WatchedPaths().contains(dir_ + "/reflectors.csv"));
  KeepTwoPointsOf(dir_ + "/points.txt", "pose_0002");
  ASSERT_TRUE(WaitFor([&] { return poses->count() == 16 && poses->item(2)->text().contains("bad_points"); },
                      kNoticeMs));
  EXPECT_TRUE(poses->item(2)->text().contains("2 points measured: a pose needs 3 or more reflectors"))
      << poses->item(2)->text().toStdString();
  poses->setCurrentRow(2);
  EXPECT_EQ(measure->ShownStatus(), "bad_points");
  EXPECT_TRUE(measure->PointsSummary().contains("15 of 16 poses fitted"));
  EXPECT_EQ(window_.Session()->State(Step::kCalibrate), StepState::kStale);

  // noise_check.json, written in the session folder, is watched from then on.
  QFile check(dir_ + "/noise_check.json");
  ASSERT_TRUE(check.open(QIODevice::WriteOnly));
  check.write("{\"ratio\": 2}\n");
  check.close();
  ASSERT_TRUE(WaitFor([&] { return window_.Session()->WatchedPaths().contains(dir_ + "/noise_check.json"); },
                      kNoticeMs));
  ASSERT_TRUE(WaitFor([&] { return measure->PointsSummary().contains("scaled by 2"); }, kNoticeMs))
      << measure->PointsSummary().toStdString();
}

TEST_F(PointsSessionTest, CalibrateFromTheGuiGivesAVerdictInTheTrackersWords) {
  ASSERT_TRUE(QDir(dir_ + "/results").removeRecursively());
  window_.Session()->Reload();
  ASSERT_TRUE(window_.ShowPanelNamed("calibrate"));
  CalibratePanel* calibrate = window_.Calibrate();
  calibrate->Run();
  ASSERT_TRUE(WaitFor([&] { return !calibrate->Job()->Running(); }));
  EXPECT_TRUE(calibrate->LastOutcome().startsWith("done")) << calibrate->LastOutcome().toStdString();
  EXPECT_FALSE(calibrate->VerdictWidget()->LevelText().isEmpty());
  const QString summary = calibrate->findChild<QLabel*>("calibrate_summary")->text();
  EXPECT_TRUE(summary.startsWith("16 poses: 12 for calibration, 4 held out")) << summary.toStdString();
  EXPECT_TRUE(summary.contains("Closure (tracker vs robot)")) << summary.toStdString();
  EXPECT_EQ(window_.Session()->State(Step::kCalibrate), StepState::kDone);
}

TEST(UiPointsNewSession, TheDialogMakesAPointsSession) {
  QTemporaryDir temp;
  NewSessionDialog dialog;
  dialog.findChild<QLineEdit*>("folder")->setText(temp.filePath("tracker"));
  dialog.findChild<QComboBox*>("robot")->setCurrentText("inria-left-hand");
  auto* instrument = dialog.findChild<QComboBox*>("instrument");
  instrument->setCurrentIndex(instrument->findData("points"));
  // 0.02 mm in the robot's unit (inria-left-hand: cm).
  EXPECT_EQ(dialog.findChild<QLineEdit*>("point_sigma")->text(), "0.002");
  dialog.findChild<QLineEdit*>("reflectors")->setText(temp.filePath("missing.csv"));
  EXPECT_FALSE(dialog.Check().ok());  // a reflector file is checked now, as session init does
  dialog.findChild<QLineEdit*>("reflectors")->clear();
  ASSERT_TRUE(dialog.Check().ok()) << dialog.Check().message();
  const SessionConfig config = dialog.Config();
  EXPECT_EQ(config.instrument, Instrument::kPoints);
  EXPECT_EQ(config.points, "points.txt");
  EXPECT_TRUE(config.camera.empty() && config.target.empty() && config.reflectors.empty());

  MainWindow window;
  window.show();
  ASSERT_TRUE(window.Session()->Create(dialog.Folder(), config).ok());
  ASSERT_TRUE(window.ShowPanelNamed("measure"));
  // The points file is not there yet: the panel says so, and the table waits for pose rows.
  EXPECT_TRUE(window.Measure()->PointsSummary().contains("They do not load"))
      << window.Measure()->PointsSummary().toStdString();
  EXPECT_EQ(window.Measure()->LegsTable()->horizontalHeaderItem(0)->text(), "pose");
}

}  // namespace
}  // namespace hexcal::ui

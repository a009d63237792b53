// The section 8 study in the GUI (ui/study_view.h) on a copy of the test
// session (make_session): none shown before it runs; a run on the worker
// keeps study/ in the session and shows where the selected subset ranks, the
// Table 5 figures and the charts; a cancelled run leaves study/ as it was;
// an edited reading marks the study stale; another session shows its own
// (none). Run under xvfb-run (ui/CMakeLists.txt).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QSurfaceFormat>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QThread>
#include <functional>

#include "session/session_study.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/main_window.h"
#include "ui/screenshot.h"
#include "ui/study_view.h"
#include "ui/tests/gui_test_support.h"
#include "ui/validate_panel.h"

namespace hexcal::ui {
namespace {

QString sessions_dir;  // argv[1]: what make_session wrote

TEST(UiStudy, RunKeepCancelStaleAndSwitch) {
  QTemporaryDir temp;
  const QString dir = temp.filePath("session");
  ASSERT_TRUE(CopyFolder(sessions_dir + "/calibrated", dir));
  MainWindow window;
  window.resize(1280, 720);
  window.show();
  ASSERT_TRUE(window.OpenSession(dir));
  ASSERT_TRUE(window.ShowPanelNamed("study"));
  StudyView* study = window.Validate()->Study();
  EXPECT_TRUE(study->RankLine()->text().contains("No section 8 study yet")) << study->RankLine()->text().toStdString();

  // 16 measured poses (12 calibration, 4 held out: the study uses them all).
  study->SetOption("select", "8");
  study->SetOption("subsets", "40");
  study->SetOption("seed", "3");
  study->Run();
  ASSERT_TRUE(WaitFor([&] { return !study->Job()->Running(); }));
  EXPECT_TRUE(study->LastOutcome().startsWith("done")) << study->LastOutcome().toStdString();
  const QString json = dir + "/study/study.json";
  ASSERT_TRUE(QFile::exists(json));
  EXPECT_TRUE(QFile::exists(dir + "/study/fig19_position.svg"));
  const StatusOr<workflow::SessionStudy>& kept = window.Session()->Study();
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_FALSE(kept->Stale());
  EXPECT_EQ(kept->record.select, 8);
  EXPECT_EQ(kept->record.random_count, 40);
  EXPECT_EQ(kept->record.measured, 16);
  EXPECT_TRUE(study->RankLine()->text().contains("validates better than")) << study->RankLine()->text().toStdString();
  EXPECT_FALSE(study->RankLine()->text().contains("Stale"));
  bool number = false;
  const double selected = study->Table()->item(0, 0)->text().toDouble(&number);  // held-out position RMS
  EXPECT_TRUE(number) << study->Table()->item(0, 0)->text().toStdString();
  EXPECT_DOUBLE_EQ(selected,
                   QString::number(kept->record.Metric(SubsetMetric::kHeldOutPosition).selected, 'g', 3).toDouble());
  EXPECT_TRUE(study->Table()->item(0, 4)->text().endsWith(" %"));
  EXPECT_TRUE(SaveWindowScreenshot(&window, temp.filePath("study.png")));

  // N as large as the session's measured poses: the study's error names the
  // option by the form's label, not by the command line's --select (issue 37).
  const QByteArray before = ReadBytes(json);
  study->SetOption("select", "16");
  study->Run();
  ASSERT_TRUE(WaitFor([&] { return !study->Job()->Running(); }));
  EXPECT_EQ(study->LastOutcome(), "failed.");
  EXPECT_TRUE(LastShownError().contains("Poses per subset (N): 16 needs more than that many measured poses"))
      << LastShownError().toStdString();
  EXPECT_FALSE(LastShownError().contains("select")) << LastShownError().toStdString();
  EXPECT_EQ(ReadBytes(json), before);
  study->SetOption("select", "8");

  // A cancelled run keeps the study as it was.
  study->SetOption("subsets", "1000000");
  study->Run();
  ASSERT_TRUE(study->Job()->Running());
  study->Job()->Cancel();
  ASSERT_TRUE(WaitFor([&] { return !study->Job()->Running(); }));
  EXPECT_EQ(study->LastOutcome(), "cancelled: study/ is unchanged.");
  EXPECT_EQ(ReadBytes(json), before);

  // A reading edited since: stale, by name.
  const LegsRow row = window.Session()->Legs().front();
  const workflow::EditOutcome edited =
      window.Session()->EditLegs(workflow::LegsEdit::SetReading(row.image, 0, row.legs[0], row.legs[0] + 1e-4));
  ASSERT_TRUE(edited.status.ok() && !edited.conflict) << edited.status.message();
  ASSERT_TRUE(window.Session()->Study().ok());
  EXPECT_TRUE(window.Session()->Study()->Stale());
  EXPECT_TRUE(study->RankLine()->text().contains("Stale:")) << study->RankLine()->text().toStdString();
  EXPECT_TRUE(study->RankLine()->text().contains("legs.csv"));

  // Another session: nothing of this one's study or run.
  ASSERT_TRUE(window.OpenSession(sessions_dir + "/session"));
  EXPECT_TRUE(study->RankLine()->text().contains("No section 8 study yet"));
  EXPECT_TRUE(study->LastOutcome().isEmpty());
  EXPECT_EQ(study->Table()->item(0, 0)->text(), "—");
}

}  // namespace
}  // namespace hexcal::ui

int main(int argc, char** argv) {
  return hexcal::ui::RunGuiTests(argc, argv, "ui_study_test", &hexcal::ui::sessions_dir);
}

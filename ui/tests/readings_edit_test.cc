// Typed input is never lost (issue 35): another program writes legs.csv
// while a reading is being typed in the Measure step's table. The editor
// stays open with its text through the reload; Enter applies it to the file
// as it is on disk (the other program's rows kept); when the other program
// changed the same cell, the question Use mine / Keep theirs decides. And
// typed readings beyond the stroke are refused, by name.
// Run under xvfb-run (ui/CMakeLists.txt).
#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QFile>
#include <QKeyEvent>
#include <QLineEdit>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <algorithm>
#include <cmath>

#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "ui/acquire_panel.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/main_window.h"
#include "ui/measure_panel.h"
#include "ui/readings_editor.h"
#include "ui/tests/gui_test_support.h"

namespace hexcal::ui {

QString sessions_dir;  // argv[1]: what make_session wrote (points_session_test.cc too)

namespace {

// L`leg` of `row` in legs.csv as it is on disk.
double OnDisk(const QString& dir, int row, int leg) {
  StatusOr<CsvTable> table = ReadCsv((dir + "/legs.csv").toStdString());
  return table.ok() ? *ParseNumber(table->rows.at(row).at(1 + leg)) : -1;
}

// Another program rewrites legs.csv with L`leg` of `row` set to `value`.
void WriteTheirs(const QString& dir, int row, int leg, double value) {
  StatusOr<CsvTable> table = ReadCsv((dir + "/legs.csv").toStdString());
  ASSERT_TRUE(table.ok());
  table->rows.at(row).at(1 + leg) = QString::number(value, 'g', 12).toStdString();
  ASSERT_TRUE(WriteCsv((dir + "/legs.csv").toStdString(), table->header, table->rows).ok());
}

class ReadingsEditTest : public SessionCopyTest {
 protected:
  void SetUp() override {
    ASSERT_TRUE(CopySession(sessions_dir + "/calibrated", "session"));
    ASSERT_TRUE(OpenCopy());
    ASSERT_TRUE(window_.ShowPanelNamed("measure"));
    table_ = window_.Measure()->LegsTable();
    ASSERT_GE(table_->rowCount(), 2);
    // The table's rows are legs.csv's, in its order: row k of one is row k of the other.
    for (int r = 0; r < 2; ++r) ASSERT_EQ(table_->item(r, 0)->text().toStdString(), window_.Session()->Legs()[r].image);
  }
  void TearDown() override { SetConflictAnswerer({}); }

  // Opens the editor of (row, L`leg`) and types `text` into it.
  QLineEdit* Type(int row, int leg, const QString& text) {
    table_->setCurrentCell(row, 1 + leg);
    table_->editItem(table_->item(row, 1 + leg));
    auto* editor = qobject_cast<QLineEdit*>(table_->indexWidget(table_->model()->index(row, 1 + leg)));
    if (editor) editor->setText(text);
    return editor;
  }
  // Waits for the folder watch to reload L`leg` of `row` as `value`.
  bool Reloaded(int row, int leg, double value) {
    return WaitFor([&] { return std::abs(window_.Session()->Legs().at(row).legs[leg] - value) < 1e-9; }, 10000);
  }
  void PressEnter(QLineEdit* editor) {
    QKeyEvent press(QEvent::KeyPress, Qt::Key_Return, Qt::NoModifier);
    QApplication::sendEvent(editor, &press);
    QApplication::processEvents();
  }
  // Types `mine` into (row, L`leg`); another program writes `theirs` into
  // the same cell meanwhile, which the editor's text survives; then Enter.
  void TypeWhileTheyWrite(int row, int leg, const QString& mine, double theirs) {
    QLineEdit* editor = Type(row, leg, mine);
    ASSERT_NE(editor, nullptr);
    WriteTheirs(dir_, row, leg, theirs);
    ASSERT_TRUE(Reloaded(row, leg, theirs));
    EXPECT_EQ(editor->text().toStdString(), mine.toStdString());
    PressEnter(editor);
  }

  ReadingsEditor* table_ = nullptr;
};

TEST_F(ReadingsEditTest, AnotherRowWrittenMeanwhileKeepsTheTypedText) {
  const double theirs = window_.Session()->Legs()[1].legs[0] + 0.5;
  QLineEdit* editor = Type(0, 0, "1.125");
  ASSERT_NE(editor, nullptr);
  WriteTheirs(dir_, 1, 0, theirs);
  ASSERT_TRUE(Reloaded(1, 0, theirs));
  // The editor is the same and holds what was typed, not the file's value.
  EXPECT_EQ(table_->indexWidget(table_->model()->index(0, 1)), editor);
  EXPECT_EQ(editor->text().toStdString(), "1.125");
  PressEnter(editor);
  EXPECT_NEAR(OnDisk(dir_, 0, 0), 1.125, 1e-9);
  EXPECT_NEAR(OnDisk(dir_, 1, 0), theirs, 1e-9);
  EXPECT_EQ(table_->item(1, 1)->text().toDouble(), QString::number(theirs, 'f', 4).toDouble());  // then shown
}

TEST_F(ReadingsEditTest, TheSameCellWrittenMeanwhileAsksUseMine) {
  QStringList asked;
  SetConflictAnswerer([&](const QString&, const QString& text) {
    asked << text;
    return true;  // Use mine
  });
  ASSERT_NO_FATAL_FAILURE(TypeWhileTheyWrite(0, 1, "2.75", 3.375));
  ASSERT_EQ(asked.size(), 1);
  EXPECT_NEAR(OnDisk(dir_, 0, 1), 2.75, 1e-9);
  EXPECT_EQ(table_->item(0, 2)->text().toDouble(), 2.75);
}

TEST_F(ReadingsEditTest, TheSameCellWrittenMeanwhileKeepsTheirsWhenAsked) {
  int asked = 0;
  SetConflictAnswerer([&](const QString&, const QString&) {
    ++asked;
    return false;  // Keep theirs
  });
  ASSERT_NO_FATAL_FAILURE(TypeWhileTheyWrite(0, 2, "3.25", 3.125));
  EXPECT_EQ(asked, 1);
  EXPECT_NEAR(OnDisk(dir_, 0, 2), 3.125, 1e-9);
  EXPECT_EQ(table_->item(0, 3)->text().toDouble(), 3.125);  // the table shows the file again
}

// Readings are checked where they enter (issue 35): beyond the leg's stroke,
// typed into the table, pasted, or typed for a capture by hand, a value is
// refused with the image, the leg and the value named; legs.csv is unchanged.
TEST_F(ReadingsEditTest, AReadingBeyondTheStrokeIsRefusedByName) {
  QStringList notes;
  QObject::connect(table_, &ReadingsEditor::Note, [&](const QString& note) { notes << note; });
  const QByteArray before = ReadBytes(dir_ + "/legs.csv");
  const QString shown = table_->item(0, 3)->text();
  for (const char* typed : {"999999", "-1e6", "1e308"}) {
    table_->item(0, 3)->setText(typed);
    EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), before) << typed;
    ASSERT_FALSE(notes.isEmpty()) << typed;
    EXPECT_TRUE(notes.back().contains(table_->item(0, 0)->text() + ": L3 = ")) << notes.back().toStdString();
    EXPECT_TRUE(notes.back().contains("outside leg 3's stroke")) << notes.back().toStdString();
    EXPECT_EQ(table_->item(0, 3)->text(), shown);  // the file's value again
  }
  EXPECT_TRUE(notes.front().contains("L3 = 999999 cm")) << notes.front().toStdString();

  EXPECT_EQ(table_->PasteReadings("1 1 1 1 1 999999\n1 1 1 1 1 1\n", 0), 0);  // nothing from the bad line on
  EXPECT_TRUE(notes.back().contains("pasted line 1 (" + table_->item(0, 0)->text() + "): L6 = 999999"))
      << notes.back().toStdString();
  EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), before);

  // By hand: the readings typed for pose 1 (the dialog's values, in a test).
  AcquirePanel* acquire = window_.Acquire();
  const QString image = dir_ + "/images/" + table_->item(0, 0)->text();
  acquire->Connect("none", "file:" + image);
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected() && !acquire->Job()->Running(); }));
  acquire->SelectPose(0);
  const Robot& robot = window_.Session()->NominalRobot();
  LegReadings typed = InverseKinematics(robot, robot.PoseFromVector(window_.Session()->Plan()[0]));
  typed[0] = 1e308;
  acquire->CapturePose(typed);
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LastOutcome().contains("not recorded: pose_0000.png: L1 = 1e+308"))
      << acquire->LastOutcome().toStdString();
  EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), before);
  EXPECT_FALSE(QFile::exists(dir_ + "/images/pose_0000.png"));
}

// Against the commanded pose too (issue 35): within the stroke but far from
// the IK length of the pose the image is captured at, a reading is refused
// by name, typed for a capture by hand or later in the table; within the
// tolerance (10 % of the stroke, reading_check.h) it is taken, and legs.csv
// records the pose it was commanded to.
TEST_F(ReadingsEditTest, AReadingFarFromTheCommandedPoseIsRefusedByName) {
  AcquirePanel* acquire = window_.Acquire();
  acquire->Connect("none", "file:" + dir_ + "/images/" + table_->item(0, 0)->text());
  ASSERT_TRUE(WaitFor([&] { return acquire->Connected() && !acquire->Job()->Running(); }));
  acquire->SelectPose(1);
  const Robot& robot = window_.Session()->NominalRobot();
  const Vector6d pose = window_.Session()->Plan()[1];
  const LegReadings needed = InverseKinematics(robot, robot.PoseFromVector(pose));
  const double tolerance = 0.1 * (robot.legs[2].stroke_max - robot.legs[2].stroke_min);  // 0.35 cm
  LegReadings typed = needed;
  // Leg 3 within its stroke, 1.5 tolerances from its length at pose 2.
  typed[2] = needed[2] + (needed[2] < 1.75 ? 1.5 : -1.5) * tolerance;
  const QByteArray before = ReadBytes(dir_ + "/legs.csv");
  acquire->CapturePose(typed);
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LastOutcome().contains("not recorded: pose_0001.png: L3 = "))
      << acquire->LastOutcome().toStdString();
  EXPECT_TRUE(acquire->LastOutcome().contains("the commanded pose needs, more than 0.35 cm (10 % of the stroke)"))
      << acquire->LastOutcome().toStdString();
  EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), before);

  typed[2] = needed[2] + 0.5 * tolerance;  // an uncalibrated robot, or one moved by hand: taken
  acquire->SelectPose(1);
  acquire->CapturePose(typed);
  ASSERT_TRUE(WaitFor([&] { return !acquire->Job()->Running(); }));
  EXPECT_TRUE(acquire->LastOutcome().contains("pose 2 recorded as pose_0001.png"))
      << acquire->LastOutcome().toStdString();
  EXPECT_EQ(acquire->Checklist()->item(1, 1)->text(), "✓ recorded");
  const auto row = std::find_if(window_.Session()->Legs().begin(), window_.Session()->Legs().end(),
                                [](const LegsRow& r) { return r.image == "pose_0001.png"; });
  ASSERT_NE(row, window_.Session()->Legs().end());
  ASSERT_TRUE(row->commanded.has_value());
  EXPECT_EQ(*row->commanded, pose);

  // The same row in the Measure step's table: L1 far from the pose's length is refused.
  int r = 0;
  while (r < table_->rowCount() && table_->item(r, 0)->text() != "pose_0001.png") ++r;
  ASSERT_LT(r, table_->rowCount());
  const QByteArray captured = ReadBytes(dir_ + "/legs.csv");
  table_->item(r, 1)->setText(QString::number(needed[0] + (needed[0] < 1.75 ? 1.5 : -1.5) * tolerance, 'g', 10));
  EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), captured);
  EXPECT_TRUE(LastShownError().contains("pose_0001.png: L1 = ")) << LastShownError().toStdString();
  EXPECT_TRUE(LastShownError().contains("the commanded pose needs")) << LastShownError().toStdString();
  table_->item(r, 1)->setText(QString::number(needed[0] + 0.25 * tolerance, 'g', 10));
  EXPECT_NE(ReadBytes(dir_ + "/legs.csv"), captured);  // near it: written
}

// Import (issue 35): a file whose reading is beyond the stroke, or far from
// the commanded pose of an image captured at one, is refused by its line,
// image, leg and value; the session's legs.csv stays as it was.
TEST_F(ReadingsEditTest, AnImportedReadingIsCheckedByLine) {
  StatusOr<CsvTable> legs = ReadCsv((dir_ + "/legs.csv").toStdString());
  ASSERT_TRUE(legs.ok());
  CsvTable typo = *legs;
  typo.rows[1][2] = "999999";  // line 3, L2
  const QString file = temp_.filePath("typo.csv");
  ASSERT_TRUE(WriteCsv(file.toStdString(), typo.header, typo.rows).ok());
  const QByteArray before = ReadBytes(dir_ + "/legs.csv");
  window_.Measure()->ImportLegs(file);
  EXPECT_EQ(ReadBytes(dir_ + "/legs.csv"), before);
  EXPECT_TRUE(LastShownError().contains("typo.csv:3: " + QString::fromStdString(typo.rows[1][0]) + ": L2 = 999999 cm"))
      << LastShownError().toStdString();
  EXPECT_TRUE(LastShownError().contains("The previous legs.csv is kept")) << LastShownError().toStdString();
  const QString good = temp_.filePath("good.csv");
  ASSERT_TRUE(WriteCsv(good.toStdString(), legs->header, legs->rows).ok());
  window_.Measure()->ImportLegs(good);  // the same readings: plausible, imported
  EXPECT_EQ(window_.Session()->Legs().size(), legs->rows.size());
}

}  // namespace
}  // namespace hexcal::ui

int main(int argc, char** argv) {
  return hexcal::ui::RunGuiTests(argc, argv, "ui_readings_edit_test", &hexcal::ui::sessions_dir);
}

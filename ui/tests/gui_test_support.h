// What the GUI tests share: waiting on the event loop for a worker's result,
// copying a test session (and a fixture with a window on a copy of its own),
// and the check that a window fits its screen with no control clipped
// (issue 35). Run under xvfb-run (ui/CMakeLists.txt).
//
//   ASSERT_TRUE(WaitFor([&] { return !panel->Job()->Running(); }));
//   EXPECT_EQ(FitProblems(&window), std::vector<std::string>{}) << "after calibrating";
#pragma once

#include <gtest/gtest.h>

#include <QByteArray>
#include <QString>
#include <QTemporaryDir>
#include <functional>
#include <string>
#include <vector>

#include "ui/main_window.h"

class QWidget;

namespace hexcal::ui {

// A GUI test binary's main: the VTK surface format, the QApplication,
// GoogleTest, argv[1] (the sessions ui/tests/make_session wrote) into
// `sessions_dir`, dialogs not interactive; then every test. `name` is in the
// usage message.
int RunGuiTests(int argc, char** argv, const char* name, QString* sessions_dir);

// Runs the event loop until `done` or the timeout; the workers deliver their
// results through it.
bool WaitFor(const std::function<bool()>& done, int timeout_ms = 60000);
bool CopyFolder(const QString& from, const QString& to);
// A file's bytes; empty when it cannot be read.
QByteArray ReadBytes(const QString& path);
// Lets the layouts settle (a few rounds of events), then returns.
void Settle(int ms = 150);

// Why `window` does not fit its screen; empty when it does. Checked:
// the window's frame inside the screen's available area; the shown panel
// (a QScrollArea named "panel_scroll") needs no scrolling; every visible
// button, field, combo box, spin box, slider, chart and table lies whole
// inside each of its ancestors (a control half outside its viewport is
// clipped; in a scroll area made to scroll, like the Plan options, only
// sideways) and has the height its text needs; every visible table shows at
// least kUsableRows rows, or all of them; every visible word-wrapped label
// has the height its text needs.
std::vector<std::string> FitProblems(QWidget* window);
constexpr int kUsableRows = 4;

// A test whose window works on a copy of one of make_session's sessions, in
// a temporary folder of its own, so that what it writes reaches no other test.
//
//   void SetUp() override {
//     ASSERT_TRUE(CopySession(sessions_dir + "/points", "points"));
//     ASSERT_TRUE(OpenCopy());
//   }
class SessionCopyTest : public ::testing::Test {
 protected:
  // `from` copied to the folder `name` in temp_; dir_ is the copy.
  bool CopySession(const QString& from, const QString& name) {
    dir_ = temp_.filePath(name);
    return CopyFolder(from, dir_);
  }
  // The window shown, with the copy open.
  bool OpenCopy() {
    window_.show();
    return window_.OpenSession(dir_);
  }

  QTemporaryDir temp_;
  QString dir_;
  MainWindow window_;  // after temp_: it closes, and stops watching the copy, before the copy goes
};

}  // namespace hexcal::ui

// Robot step: the nominal robot of the session (its file, legs, strokes) and
// the 3D view, with the planned poses to scrub through and show as ghosts,
// workspace samples, and the camera and target once registered.
//
//   auto* robot = new RobotPanel(session);
//   robot->ShowPlannedPose(0);  // the platform at the plan's first pose
#pragma once

#include <QWidget>

#include "ui/qt_fwd.h"
#include "ui/session_state.h"

namespace hexcal::ui {

class RobotView;

class RobotPanel : public QWidget {
  Q_OBJECT
 public:
  RobotPanel(SessionState* session, QWidget* parent = nullptr);
  RobotView* View() const { return view_; }

 public slots:
  void Refresh();
  // Shows planned pose `index` (0-based) in the 3D view.
  void ShowPlannedPose(int index);

 private:
  void UpdateOverlays();

  SessionState* session_;
  RobotView* view_;
  QLabel* summary_;
  QTableWidget* legs_;
  QSlider* scrub_;
  QLabel* scrub_label_;
  QCheckBox* ghosts_;
  QCheckBox* samples_;
  QCheckBox* camera_;
  std::vector<Vector6d> workspace_samples_;
  QString shown_session_;
};

}  // namespace hexcal::ui

// The 3D view widget: RobotScene in a QVTKOpenGLNativeWidget, with Reset view
// and Save screenshot buttons. Rotate with the left mouse button, zoom with
// the wheel or the right button, pan with the middle button (VTK trackball).
//
//   auto* view = new RobotView;
//   view->Scene().SetRobot(robot);
//   view->Render();
#pragma once

#include <QWidget>

#include "ui/robot_scene.h"

class QVTKOpenGLNativeWidget;
class QLabel;

namespace hexcal::ui {

class RobotView : public QWidget {
  Q_OBJECT
 public:
  explicit RobotView(QWidget* parent = nullptr);
  ~RobotView() override;

  RobotScene& Scene() { return scene_; }
  // Re-renders after the scene changed.
  void Render();
  QImage Snapshot();
  // The legend line under the view: stroke use of each leg.
  void UpdateLegend();

 public slots:
  void ResetView();
  void SaveScreenshot();

 private:
  RobotScene scene_;
  QVTKOpenGLNativeWidget* vtk_widget_;
  QLabel* legend_;
};

}  // namespace hexcal::ui

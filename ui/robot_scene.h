// The VTK scene of the 3D view: base, legs and platform at one pose (legs
// coloured by stroke use: green at mid-stroke, red at an end, magenta beyond),
// the planned poses as ghosts of the platform, workspace samples as points,
// the camera frustum and the target. Pure VTK: robot_view.h puts it in a widget.
//
//   RobotScene scene;
//   scene.SetRobot(robot);
//   scene.SetPose(pose);  // legs coloured by StrokeUse
#pragma once

#include <vtkActor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <array>
#include <optional>
#include <vector>

#include "core/robot.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::ui {

// Where the camera and the target are (session frames, robot unit).
struct CameraTargetFrames {
  Pose base_from_camera;
  Pose platform_from_target;
  Camera camera;
  Target target;
  double target_scale = 1;  // robot unit per target unit
};

// 0 at mid-stroke, 1 at either end; above 1 outside the stroke.
double StrokeUse(const Leg& leg, double reading);

class RobotScene {
 public:
  RobotScene();
  vtkRenderer* Renderer() const { return renderer_; }

  void SetRobot(const Robot& robot);
  void SetPose(const Vector6d& pose);
  void SetGhosts(const std::vector<Vector6d>& poses);
  void SetWorkspaceSamples(const std::vector<Vector6d>& poses);
  void SetCameraAndTarget(const std::optional<CameraTargetFrames>& frames);
  void ResetView();

  // Stroke use per leg at the current pose (tests and the legend).
  const std::array<double, kNumLegs>& LegStrokeUse() const { return stroke_use_; }
  // Outside the stroke by more than the planner's tolerance (core/constraints.h):
  // a reading a few ulps past an end, as a boundary pose gives, is not.
  const std::array<bool, kNumLegs>& LegBeyondStroke() const { return beyond_stroke_; }

 private:
  void UpdateTarget();

  Robot robot_;
  Pose pose_;
  std::optional<CameraTargetFrames> frames_;
  std::array<double, kNumLegs> stroke_use_{};
  std::array<bool, kNumLegs> beyond_stroke_{};
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> base_, platform_, ghosts_, samples_, frustum_, target_;
  std::array<vtkSmartPointer<vtkActor>, kNumLegs> legs_;
};

}  // namespace hexcal::ui

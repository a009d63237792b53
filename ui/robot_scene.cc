#include "ui/robot_scene.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkLineSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTubeFilter.h>

#include <algorithm>
#include <cmath>

#include "core/constraints.h"
#include "core/inverse_kinematics.h"

namespace hexcal::ui {
namespace {

vtkSmartPointer<vtkActor> MakeActor(double r, double g, double b, double opacity = 1.0) {
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetAmbient(0.35);  // faces seen from below stay readable
  return actor;
}

void SetGeometry(vtkActor* actor, vtkPolyData* data) {
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(data);
}

// Closed polygons (one per entry of `loops`) as filled faces and outlines.
vtkSmartPointer<vtkPolyData> Polygons(const std::vector<std::vector<Eigen::Vector3d>>& loops, bool filled) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (const auto& loop : loops) {
    const vtkIdType first = points->GetNumberOfPoints();
    for (const Eigen::Vector3d& p : loop) points->InsertNextPoint(p.data());
    cells->InsertNextCell(static_cast<vtkIdType>(loop.size() + (filled ? 0 : 1)));
    for (size_t k = 0; k < loop.size(); ++k) cells->InsertCellPoint(first + k);
    if (!filled) cells->InsertCellPoint(first);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  if (filled) {
    data->SetPolys(cells);
  } else {
    data->SetLines(cells);
  }
  return data;
}

vtkSmartPointer<vtkPolyData> Segments(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (const auto& [from, to] : segments) {
    const vtkIdType a = points->InsertNextPoint(from.data());
    const vtkIdType b = points->InsertNextPoint(to.data());
    cells->InsertNextCell(2);
    cells->InsertCellPoint(a);
    cells->InsertCellPoint(b);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(cells);
  return data;
}

std::vector<Eigen::Vector3d> PlatformLoop(const Robot& robot, const Pose& pose) {
  std::vector<Eigen::Vector3d> loop;
  for (const Leg& leg : robot.legs) loop.push_back(pose * leg.b_in_platform);
  return loop;
}

double RobotSize(const Robot& robot) {
  double size = 1;
  for (const Leg& leg : robot.legs) size = std::max({size, leg.a_in_base.norm(), leg.stroke_max});
  return size;
}

}  // namespace

double StrokeUse(const Leg& leg, double reading) {
  const double half = 0.5 * (leg.stroke_max - leg.stroke_min);
  if (half <= 0) return 0;
  return std::abs(reading - 0.5 * (leg.stroke_min + leg.stroke_max)) / half;
}

RobotScene::RobotScene() : renderer_(vtkSmartPointer<vtkRenderer>::New()) {
  renderer_->SetBackground(0.96, 0.96, 0.97);
  renderer_->SetBackground2(0.80, 0.84, 0.90);
  renderer_->GradientBackgroundOn();
  base_ = MakeActor(0.35, 0.38, 0.45);
  platform_ = MakeActor(0.20, 0.45, 0.80, 0.9);
  ghosts_ = MakeActor(0.20, 0.45, 0.80, 0.35);
  samples_ = MakeActor(0.45, 0.45, 0.45, 0.6);
  samples_->GetProperty()->SetPointSize(3);
  frustum_ = MakeActor(0.85, 0.45, 0.05);
  frustum_->GetProperty()->SetLineWidth(2);
  target_ = MakeActor(0.97, 0.97, 0.92, 0.75);  // the printed sheet
  for (auto& leg : legs_) leg = MakeActor(0.2, 0.7, 0.2);
  for (vtkActor* actor : {base_.Get(), platform_.Get(), ghosts_.Get(), samples_.Get(), frustum_.Get(), target_.Get()})
    renderer_->AddActor(actor);
  for (auto& leg : legs_) renderer_->AddActor(leg);
  frustum_->SetVisibility(false);
  target_->SetVisibility(false);
}

void RobotScene::SetRobot(const Robot& robot) {
  robot_ = robot;
  std::vector<Eigen::Vector3d> base;
  for (const Leg& leg : robot.legs) base.push_back(leg.a_in_base);
  SetGeometry(base_, Polygons({base}, true));
  SetPose(WorkspaceCentre(robot));
}

void RobotScene::SetPose(const Vector6d& pose_vector) {
  pose_ = robot_.PoseFromVector(pose_vector);
  SetGeometry(platform_, Polygons({PlatformLoop(robot_, pose_)}, true));
  const LegReadings readings = InverseKinematics(robot_, pose_);
  const double radius = 0.018 * RobotSize(robot_);
  for (int i = 0; i < kNumLegs; ++i) {
    auto line = vtkSmartPointer<vtkLineSource>::New();
    const Eigen::Vector3d a = robot_.legs[i].a_in_base, b = pose_ * robot_.legs[i].b_in_platform;
    line->SetPoint1(a.data());
    line->SetPoint2(b.data());
    auto tube = vtkSmartPointer<vtkTubeFilter>::New();
    tube->SetInputConnection(line->GetOutputPort());
    tube->SetRadius(radius);
    tube->SetNumberOfSides(12);
    tube->Update();
    SetGeometry(legs_[i], tube->GetOutput());
    stroke_use_[i] = StrokeUse(robot_.legs[i], readings[i]);
    const double use = std::min(stroke_use_[i], 1.0);
    beyond_stroke_[i] = !WithinStroke(robot_.legs[i], readings[i]);
    if (beyond_stroke_[i]) {
      legs_[i]->GetProperty()->SetColor(0.85, 0.0, 0.85);  // beyond the stroke
    } else {
      legs_[i]->GetProperty()->SetColor(0.15 + 0.8 * use, 0.7 * (1 - use) + 0.15, 0.15);
    }
  }
  UpdateTarget();
}

void RobotScene::SetGhosts(const std::vector<Vector6d>& poses) {
  std::vector<std::vector<Eigen::Vector3d>> loops;
  for (const Vector6d& pose : poses) loops.push_back(PlatformLoop(robot_, robot_.PoseFromVector(pose)));
  SetGeometry(ghosts_, Polygons(loops, false));
}

void RobotScene::SetWorkspaceSamples(const std::vector<Vector6d>& poses) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (const Vector6d& pose : poses) {
    cells->InsertNextCell(1);
    cells->InsertCellPoint(points->InsertNextPoint(pose[0], pose[1], pose[2]));
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetVerts(cells);
  SetGeometry(samples_, data);
}

void RobotScene::SetCameraAndTarget(const std::optional<CameraTargetFrames>& frames) {
  frames_ = frames;
  frustum_->SetVisibility(frames.has_value());
  target_->SetVisibility(frames.has_value());
  if (!frames) return;
  // The image corners pushed out to the depth of the robot's platform.
  const Pose& camera = frames->base_from_camera;
  const double depth = std::max(1.0, (camera.position - pose_.position).norm());
  const Camera& c = frames->camera;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  std::vector<Eigen::Vector3d> far;
  for (auto [u, v] : {std::pair{0, 0}, {c.width, 0}, {c.width, c.height}, {0, c.height}}) {
    const Eigen::Vector3d ray((u - c.cx) / c.fx, (v - c.cy) / c.fy, 1.0);
    far.push_back(camera * (depth * ray));
    segments.emplace_back(camera.position, far.back());
  }
  for (int k = 0; k < 4; ++k) segments.emplace_back(far[k], far[(k + 1) % 4]);
  SetGeometry(frustum_, Segments(segments));
  UpdateTarget();
}

void RobotScene::UpdateTarget() {
  if (!frames_) return;
  const Target& t = frames_->target;
  const double s = frames_->target_scale, m = t.margin;
  const Pose base_from_target{pose_.position + pose_.rotation * frames_->platform_from_target.position,
                              pose_.rotation * frames_->platform_from_target.rotation};
  const double x0 = t.TagsMin().x() - m, y0 = t.TagsMin().y() - m;
  const double x1 = x0 + t.Width() + 2 * m, y1 = y0 + t.Height() + 2 * m;
  std::vector<Eigen::Vector3d> sheet;
  for (auto [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})
    sheet.push_back(base_from_target * Eigen::Vector3d(s * x, s * y, 0.0));
  SetGeometry(target_, Polygons({sheet}, true));
}

void RobotScene::ResetView() {
  // From the front-right and above the platform, looking at mid-height; then
  // VTK fits every visible actor (frustum and ghosts included).
  const double height = std::max(1.0, std::abs(pose_.position.z()));
  const Eigen::Vector3d focus(0, 0, 0.5 * pose_.position.z());
  const Eigen::Vector3d eye = focus + 2.5 * height * Eigen::Vector3d(0.55, -0.65, 0.6).normalized();
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(focus.data());
  camera->SetPosition(eye.data());
  camera->SetViewUp(0, 0, 1);
  // Fit the robot, its ghosts and the target; the camera frustum may leave
  // the frame (it reaches far above the robot), zoom out to see it whole.
  double bounds[6] = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (vtkActor* actor : {base_.Get(), platform_.Get(), ghosts_.Get(), target_.Get()}) {
    if (!actor->GetVisibility() || !actor->GetMapper()->GetInput()) continue;
    const double* b = actor->GetBounds();
    if (b[0] > b[1]) continue;  // empty geometry
    for (int k = 0; k < 3; ++k) {
      bounds[2 * k] = std::min(bounds[2 * k], b[2 * k]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], b[2 * k + 1]);
    }
  }
  if (bounds[0] <= bounds[1]) {
    renderer_->ResetCamera(bounds);
    camera->Zoom(1.1);
  } else {
    renderer_->ResetCamera();
  }
  renderer_->ResetCameraClippingRange();
}

}  // namespace hexcal::ui

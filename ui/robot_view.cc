#include "ui/robot_view.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

#include "ui/error_dialog.h"

namespace hexcal::ui {

RobotView::RobotView(QWidget* parent) : QWidget(parent), vtk_widget_(new QVTKOpenGLNativeWidget(this)) {
  vtk_widget_->setObjectName("vtk_view");
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  vtk_widget_->setRenderWindow(window);
  window->AddRenderer(scene_.Renderer());
  auto style = vtkSmartPointer<vtkInteractorStyleTrackballCamera>::New();
  window->GetInteractor()->SetInteractorStyle(style);
  vtk_widget_->setMinimumSize(360, 300);

  auto* reset = new QPushButton("Reset view");
  auto* screenshot = new QPushButton("Save screenshot…");
  legend_ = new QLabel;
  legend_->setTextFormat(Qt::PlainText);  // file names are shown as they are, never as HTML
  legend_->setObjectName("stroke_legend");
  legend_->setWordWrap(true);  // one line of six legs is wider than the view at 1280 px
  connect(reset, &QPushButton::clicked, this, &RobotView::ResetView);
  connect(screenshot, &QPushButton::clicked, this, &RobotView::SaveScreenshot);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(legend_, 1);
  buttons->addWidget(reset);
  buttons->addWidget(screenshot);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(vtk_widget_, 1);
  layout->addLayout(buttons);
}

RobotView::~RobotView() = default;

void RobotView::Render() {
  UpdateLegend();
  vtk_widget_->renderWindow()->Render();
  vtk_widget_->update();
}

void RobotView::UpdateLegend() {
  QString text = "stroke use (0 mid, 1 end):";
  for (int i = 0; i < kNumLegs; ++i) {
    const double use = scene_.LegStrokeUse()[i];
    text += QString(" L%1 %2%3").arg(i + 1).arg(use, 0, 'f', 2).arg(scene_.LegBeyondStroke()[i] ? " beyond!" : "");
  }
  legend_->setText(text);
}

void RobotView::ResetView() {
  scene_.ResetView();
  Render();
}

QImage RobotView::Snapshot() {
  vtk_widget_->renderWindow()->Render();
  return vtk_widget_->grabFramebuffer();
}

void RobotView::SaveScreenshot() {
  const QString file = QFileDialog::getSaveFileName(this, "Save 3D view", "robot-view.png", "PNG image (*.png)");
  if (file.isEmpty()) return;
  if (!Snapshot().save(file, "PNG"))
    ShowError(this, "Screenshot", "Could not write " + file + ": check the folder is writable.");
}

}  // namespace hexcal::ui

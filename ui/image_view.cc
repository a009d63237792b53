#include "ui/image_view.h"

#include <QGraphicsPixmapItem>
#include <QGraphicsScene>
#include <QGraphicsSimpleTextItem>
#include <QKeyEvent>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace hexcal::ui {
namespace {

constexpr double kWheelStep = 1.25;  // per notch
constexpr double kMinZoom = 0.02, kMaxZoom = 40;

}  // namespace

ImageView::ImageView(QWidget* parent) : QGraphicsView(parent) {
  setScene(new QGraphicsScene(this));
  pixmap_ = scene()->addPixmap(QPixmap());
  pixmap_->setTransformationMode(Qt::SmoothTransformation);
  message_ = scene()->addSimpleText("");
  setDragMode(QGraphicsView::ScrollHandDrag);
  setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
  setRenderHint(QPainter::SmoothPixmapTransform);
  setBackgroundBrush(QColor(40, 40, 40));
  setMinimumSize(240, 180);
  setToolTip("Wheel or +/− to zoom, drag to pan, double click or 0 to fit");
}

void ImageView::SetImage(const QImage& image) {
  const bool same_size = !pixmap_->pixmap().isNull() && pixmap_->pixmap().size() == image.size();
  message_->setText("");
  pixmap_->setPixmap(QPixmap::fromImage(image));
  scene()->setSceneRect(pixmap_->boundingRect());
  if (!same_size || fitted_) Fit();
}

void ImageView::SetMessage(const QString& text) {
  pixmap_->setPixmap(QPixmap());
  message_->setBrush(Qt::white);
  message_->setText(text);
  scene()->setSceneRect(message_->boundingRect());
  resetTransform();
  fitted_ = true;
}

bool ImageView::HasImage() const { return !pixmap_->pixmap().isNull(); }

QString ImageView::Message() const { return message_->text(); }

void ImageView::ZoomBy(double factor) {
  if (!HasImage()) return;
  const double zoom = std::clamp(Zoom() * factor, kMinZoom, kMaxZoom);
  scale(zoom / Zoom(), zoom / Zoom());
  fitted_ = false;
}

void ImageView::Fit() {
  if (!HasImage()) return;
  fitInView(pixmap_, Qt::KeepAspectRatio);
  fitted_ = true;
}

double ImageView::Zoom() const { return transform().m11(); }

void ImageView::wheelEvent(QWheelEvent* event) {
  const double notches = event->angleDelta().y() / 120.0;
  if (notches != 0) ZoomBy(std::pow(kWheelStep, notches));
  event->accept();
}

void ImageView::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Plus || event->key() == Qt::Key_Equal) return ZoomBy(kWheelStep);
  if (event->key() == Qt::Key_Minus) return ZoomBy(1 / kWheelStep);
  if (event->key() == Qt::Key_0) return Fit();
  QGraphicsView::keyPressEvent(event);
}

void ImageView::mouseDoubleClickEvent(QMouseEvent* event) {
  Fit();
  event->accept();
}

void ImageView::resizeEvent(QResizeEvent* event) {
  QGraphicsView::resizeEvent(event);
  if (fitted_) Fit();
}

}  // namespace hexcal::ui

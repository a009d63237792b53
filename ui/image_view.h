// An image the operator can zoom into (the detection overlay of the Measure
// step, the Acquire step's live view): it fits the view until zoomed; the
// wheel (or +/−) zooms about the cursor, dragging pans, a double click or 0
// fits again. Without an image it shows a sentence.
//
//   auto* view = new ImageView;
//   view->SetImage(shown.image);  // or SetMessage("No image yet")
//   view->ZoomBy(2);
#pragma once

#include <QGraphicsView>
#include <QImage>
#include <QString>

class QGraphicsPixmapItem;
class QGraphicsSimpleTextItem;

namespace hexcal::ui {

class ImageView : public QGraphicsView {
  Q_OBJECT
 public:
  explicit ImageView(QWidget* parent = nullptr);

  void SetImage(const QImage& image);  // keeps the zoom when the size is the same (a live view)
  void SetMessage(const QString& text);  // no image: the sentence instead
  bool HasImage() const;
  QString Message() const;
  void ZoomBy(double factor);
  void Fit();
  double Zoom() const;  // screen pixels per image pixel

 protected:
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  QGraphicsPixmapItem* pixmap_;
  QGraphicsSimpleTextItem* message_;
  bool fitted_ = true;  // follows the view's size until the operator zooms
};

}  // namespace hexcal::ui

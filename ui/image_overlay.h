// One image as the operator checks it: detected tags (outline and id, green),
// the target reprojected with the estimated board pose (red corner crosses),
// the pose status and the reprojection RMS. Runs on a worker thread: it makes
// a QImage (thread-safe), never a widget or pixmap.
#pragma once

#include <QImage>
#include <QString>

#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::ui {

struct OverlayResult {
  QImage image;    // the photograph with the overlay; null when unreadable
  QString status;  // "ok", "too_few_tags", ... and the message
  double rms_px = 0;
  int tags = 0;
  bool ok = false;
};

OverlayResult DetectAndDraw(const QString& file, const Camera& camera, const Target& target);

}  // namespace hexcal::ui

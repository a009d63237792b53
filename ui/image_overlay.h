// One image as the operator checks it: detected tags (outline and id, green),
// the target reprojected with the estimated board pose (red corner crosses),
// the pose status and the reprojection RMS. Runs on a worker thread: it makes
// a QImage (thread-safe), never a widget or pixmap.
//
//   OverlayResult shown = DetectAndDraw(file, camera, target);  // on a worker
//   const QString problem = ReadinessProblem(shown);             // empty: ready
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
  int tags = 0;        // target tags detected
  int board_tags = 0;  // tags on the target
  bool ok = false;
  // Readiness of a live frame (the Acquire step): the whole board inside the
  // image at the estimated pose, and the sharpness as the variance of the
  // Laplacian (grey levels²; a focused, unblurred board is in the hundreds).
  bool whole_board_in_view = false;
  double sharpness = 0;
};

OverlayResult DetectAndDraw(const QString& file, const Camera& camera, const Target& target);
// The same on a frame in memory (CV_8UC1, or CV_8UC3 in BGR order).
OverlayResult DetectAndDraw(const cv::Mat& frame, const Camera& camera, const Target& target);

// What a frame lacks to be captured ("" when ready): the thresholds of the
// Acquire step's indicators (docs/gui.md).
constexpr double kReadyMaxRmsPx = 0.5;
constexpr double kReadyMinSharpness = 50;
QString ReadinessProblem(const OverlayResult& overlay);

}  // namespace hexcal::ui

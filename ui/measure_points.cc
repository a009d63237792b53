// MeasurePanel for a points session (docs/session.md, "Points sessions"):
// no images, no camera; the points file and the reflectors named, each
// legs.csv pose with the fit of its points (workflow/point_session.h).
// The panel's layout and the camera session's list are in measure_panel.cc.
#include <QFileInfo>
#include <QGridLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSplitter>
#include <algorithm>

#include "ui/image_view.h"
#include "ui/measure_panel.h"
#include "ui/quantity_format.h"
#include "ui/text_wrap.h"

namespace hexcal::ui {
namespace {

QString Text(const std::string& text) { return QString::fromStdString(text); }

// "ok, RMS 0.00298 cm" (with `points`: ", 4 points"), or the status and why not.
QString FitLine(const workflow::PointPoseFit& fit, const QString& unit, bool points) {
  if (fit.status != "ok") return Text(fit.status) + ": " + Text(fit.message);
  return QString("ok, RMS %1").arg(FormatLength(fit.rms, unit)) +
         (points ? QString(", %1 points").arg(fit.points) : QString());
}

}  // namespace

void MeasurePanel::ShowInstrument() {
  const bool points = session_->IsPointsSession();
  if (arranged_for_points_ == points) return;
  arranged_for_points_ = points;
  list_title_->setText(points ? "Poses of legs.csv (each fitted to the reflectors)"
                              : "Images (status from camera_poses.csv)");
  points_summary_->setVisible(points);
  picture_info_->setToolTip(QString());
  picture_->setVisible(!points);  // the progress bar shows only while a job runs (ShowProgressOn)
  for (QPushButton* button : camera_buttons_) button->setVisible(!points);
  // Without an image, the list's lines (a bad pose's reason) get the room.
  top_->setSizes(points ? QList<int>{500, 500} : QList<int>{320, 700});
  points_summary_->setToolTip(points ? "A points session has no images or camera: each pose comes from its points "
                                       "(fitted to the reflectors), and the Calibrate step fits them again."
                                     : QString());
  import_legs_->setToolTip(QString("Use a CSV %1,L1..L6[,holdout] as the session's legs.csv")
                               .arg(points ? "pose" : "image"));
  LayOutButtons();
}

// Two a row, without the gaps the hidden ones would leave.
void MeasurePanel::LayOutButtons() {
  for (QPushButton* button : all_buttons_) buttons_->removeWidget(button);
  const bool points = arranged_for_points_.value_or(false);
  int placed = 0;
  for (QPushButton* button : all_buttons_) {
    const bool camera_only = std::find(camera_buttons_.begin(), camera_buttons_.end(), button) != camera_buttons_.end();
    if (points && camera_only) continue;  // hidden
    buttons_->addWidget(button, placed / 2, placed % 2);
    ++placed;
  }
}

QString MeasurePanel::PointsSummary() const { return points_summary_->text().remove(QChar(0x200B)); }

void MeasurePanel::FillPoseList() {
  fits_.clear();
  images_->clear();  // row k is fits_[k] (an image put in images/ anyway is not listed)
  const SessionConfig& config = session_->Config();
  const QString unit = LengthUnitName(session_->NominalRobot().length_unit);
  std::vector<std::string> poses;
  for (const LegsRow& row : session_->Legs()) poses.push_back(row.image);
  const std::string dir = session_->Dir().toStdString();
  StatusOr<workflow::PointFiles> files = workflow::SessionPointFiles(dir, config);
  StatusOr<workflow::PointPoseReview> review =
      files.ok() ? workflow::ReviewPointPoses(*files, poses) : StatusOr<workflow::PointPoseReview>(files.status());
  QString summary = QString("Points: %1 (σ %2 per coordinate where the file gives none). ")
                        .arg(Text(config.points), FormatLength(config.point_sigma, unit));
  if (!review.ok()) {
    summary += "They do not load: " + session_->InSession(Text(review.status().message()));
  } else {
    const QString reflectors = config.reflectors.empty() ? QString("estimated from the poses (no reflector file)")
                                                         : "from " + Text(config.reflectors);
    summary += QString("Reflectors: %1, %2. %3 of %4 poses fitted.")
                   .arg(review->reflectors)
                   .arg(reflectors)
                   .arg(review->fitted)
                   .arg(poses.size());
    if (files->noise_factor > 1)
      summary += QString(" The fits' σ are scaled by %1 (noise_check.json).").arg(FormatRatio(files->noise_factor));
    fits_ = review->poses;
  }
  points_summary_->setText(Breakable(summary));
  for (const workflow::PointPoseFit& fit : fits_) {
    // Short enough for the list's width; the line beside it has the rest.
    auto* item = new QListWidgetItem(Text(fit.pose) + "  —  " + FitLine(fit, unit, false));
    item->setToolTip(FitLine(fit, unit, true));
    item->setForeground(fit.status == "ok" ? Qt::darkGreen : Qt::red);
    images_->addItem(item);
  }
}

void MeasurePanel::ShowPose(int row) {
  if (row < 0 || row >= static_cast<int>(fits_.size())) {
    shown_status_.clear();
    picture_info_->clear();
    return;
  }
  const workflow::PointPoseFit& fit = fits_[row];
  shown_status_ = Text(fit.status);
  const QString unit = LengthUnitName(session_->NominalRobot().length_unit);
  picture_info_->setText(Breakable(Text(fit.pose) + ": " + FitLine(fit, unit, true) +
                                   (fit.status == "ok" ? QString() : " — left out of the calibration")));
  picture_info_->setToolTip(fit.status == "ok" ? "RMS: of the distances of its points to the reflectors moved "
                                                 "by the fitted pose"
                                               : QString());
}

}  // namespace hexcal::ui

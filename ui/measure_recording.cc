// MeasurePanel's recording actions: images from a folder, leg readings from
// a file, camera intrinsics from target images.
// The panel's layout, preview and batch measurement are in measure_panel.cc.
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QPlainTextEdit>
#include <QSpinBox>
#include <filesystem>

#include "core/session_lock.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/measure_panel.h"
#include "ui/quantity_format.h"
#include "vision/intrinsics.h"
#include "vision/measure.h"
#include "workflow/intrinsics_step.h"

namespace hexcal::ui {
namespace {

QString Message(const Status& status) { return QString::fromStdString(status.message()); }

}  // namespace

void MeasurePanel::LoadImageFolder(const QString& chosen) {
  if (!session_->IsOpen()) return ShowError(this, "Load images", "Open or create a session first (File menu).");
  if (session_->IsPointsSession())
    return ShowError(this, "Load images", "A points session has no images: its poses come from the points file.");
  const QString folder = chosen.isEmpty() ? QFileDialog::getExistingDirectory(this, "Folder of images") : chosen;
  if (folder.isEmpty()) return;
  StatusOr<std::vector<std::string>> files = ListImages(folder.toStdString());
  if (!files.ok()) return ShowError(this, "Load images", Message(files.status()));
  if (Status inside = workflow::CheckWritableInside(session_->Dir().toStdString(), "images"); !inside.ok())
    return ShowError(this, "Load images", Message(inside));
  StatusOr<SessionLock> lock = SessionLock::Acquire(session_->Dir().toStdString(), LockWait::kBriefly);
  if (!lock.ok()) return ShowError(this, "Load images", Message(lock.status()));
  int copied = 0;
  for (const std::string& file : *files) {
    const QString target = QDir(QString::fromStdString(session_->Paths().images))
                               .filePath(QFileInfo(QString::fromStdString(file)).fileName());
    if (QFileInfo::exists(target)) continue;  // recorded images are never overwritten
    copied += QFile::copy(QString::fromStdString(file), target);
  }
  status_->setText(QString("copied %1 of %2 into images/ (existing names kept).")
                       .arg(copied)
                       .arg(FormatCount(static_cast<long long>(files->size()), "image")));
  session_->Reload();
}

void MeasurePanel::ImportLegs(const QString& chosen) {
  if (!session_->IsOpen()) return ShowError(this, "Import readings", "Open or create a session first (File menu).");
  const QString file =
      chosen.isEmpty() ? QFileDialog::getOpenFileName(this, "Leg readings", {}, "CSV (*.csv)") : chosen;
  if (file.isEmpty()) return;
  // Replaces legs.csv under the lock; a file that does not load leaves the old one.
  const Status imported = workflow::ImportLegsFile(session_->Dir().toStdString(), file.toStdString());
  session_->Reload();
  if (!imported.ok()) ShowError(this, "Import readings", Message(imported) + "\nThe previous legs.csv is kept.");
}

void MeasurePanel::IntrinsicsFromFolder(const QString& chosen) {
  if (session_->IsPointsSession())
    return ShowError(this, "Intrinsics", "A points session has no camera: its poses come from the points file.");
  if (!session_->IsOpen() || !session_->SessionTarget())
    return ShowError(this, "Intrinsics", "Open a session whose target loads first.");
  const QString folder = chosen.isEmpty() ? QFileDialog::getExistingDirectory(this, "Folder of target images") : chosen;
  if (folder.isEmpty()) return;
  StatusOr<std::vector<std::string>> files = ListImages(folder.toStdString());
  if (!files.ok()) return ShowError(this, "Intrinsics", Message(files.status()));
  const Target target = *session_->SessionTarget();
  const std::string out = (std::filesystem::path(session_->Dir().toStdString()) / "camera.yaml").string();
  const std::string dir = session_->Dir().toStdString();
  StartJob("intrinsics", [this, files = *files, target, out, dir](const JobContext& context) -> GuiContinuation {
    // camera.yaml is a session file: written under the session lock.
    StatusOr<SessionLock> lock = SessionLock::Acquire(dir, LockWait::kBriefly);
    StatusOr<workflow::IntrinsicsOutcome> outcome =
        lock.ok() ? workflow::CalibrateCameraFromFiles(files, target, IntrinsicsOptions{}, out, "", context)
                  : StatusOr<workflow::IntrinsicsOutcome>(lock.status());
    if (!outcome.ok())
      return [this, s = outcome.status()] {
        // The "intrinsics…" line of the job's start does not outlive it.
        status_->setText(s.cancelled() ? "intrinsics cancelled: camera.yaml is unchanged." : "intrinsics failed.");
        if (!s.cancelled())
          ShowError(this, "Intrinsics", Message(s) + "\nUse more views of the target, tilted and filling the image.");
      };
    const IntrinsicsResult* result = &outcome->result;
    QString report = QString("%1 of %2 used, RMS %3\nfx %4, fy %5, cx %6, cy %7")
                         .arg(result->used_views)
                         .arg(FormatCount(static_cast<long long>(result->views.size()), "view"))
                         .arg(FormatPixels(result->rms_px))
                         .arg(FormatPixelCoordinate(result->camera.fx), FormatPixelCoordinate(result->camera.fy),
                              FormatPixelCoordinate(result->camera.cx), FormatPixelCoordinate(result->camera.cy));
    if (result->std_dev.size() >= 4)  // empty for a model whose calibration gives none
      report += QString(" (σ %1, %2, %3, %4)")
                    .arg(FormatPixels(result->std_dev[0]), FormatPixels(result->std_dev[1]),
                         FormatPixels(result->std_dev[2]), FormatPixels(result->std_dev[3]));
    report += "\n";
    for (const CalibrationView& view : result->views)
      report += QString("%1: %2\n")
                    .arg(QString::fromStdString(std::filesystem::path(view.file).filename().string()),
                         view.used ? "RMS " + FormatPixels(view.rms_px)
                                   : "not used, " + QString::fromStdString(view.reason));
    return [this, report] {
      report_->setPlainText(report);
      report_->setVisible(true);
      const bool used = ApplySessionEdit(
          this, "Intrinsics", [this](bool overwrite) { return session_->SetCamera("camera.yaml", overwrite); });
      status_->setText(used ? "intrinsics: camera.yaml written; the session uses it (measure the images again)."
                            : "intrinsics: camera.yaml written; the session's camera is unchanged.");
    };
  });
}

}  // namespace hexcal::ui

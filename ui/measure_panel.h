// Measure step: the session's images (load a folder; the Acquire step
// captures them pose by pose), the leg readings (enter in the table or
// import a CSV), each image with its detected tags and reprojected board, its
// status and RMS; the batch measurement into camera_poses.csv; camera
// intrinsics from a folder of target images, with their report.
#pragma once

#include <QWidget>
#include <map>

#include "ui/background_job.h"
#include "ui/readings_editor.h"
#include "ui/session_state.h"

class QLabel;
class QLayout;
class QListWidget;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace hexcal::ui {

class BackgroundJob;
class ImageView;

class MeasurePanel : public QWidget {
  Q_OBJECT
 public:
  MeasurePanel(SessionState* session, QWidget* parent = nullptr);
  BackgroundJob* Job() const { return job_; }
  BackgroundJob* PreviewJob() const { return preview_; }
  QListWidget* ImageList() const { return images_; }
  ImageView* Picture() const { return picture_; }
  ReadingsEditor* LegsTable() const { return legs_; }
  const QString& ShownStatus() const { return shown_status_; }

 public slots:
  void Refresh();
  // Another session was opened: its first image, no texts of the last one.
  void ResetForSession();
  void LoadImageFolder(const QString& folder = {});
  void ImportLegs(const QString& file = {});
  void MeasureAll();
  void IntrinsicsFromFolder(const QString& folder = {});
  void ShowImage(int row);

 private:
  void ArrangeWidgets(QLayout* buttons);
  bool CameraAndTargetReady(const QString& step);
  void ShowReadingsHint();  // how many images lack readings, after every refill
  std::map<QString, QString> ToMeasureAgain() const;  // image name: why its measurement is stale
  void StartJob(const QString& what, JobWork work);

  SessionState* session_;
  BackgroundJob* job_;      // measuring, capture, intrinsics: one at a time
  BackgroundJob* preview_;  // the selected image's detection
  QListWidget* images_;
  ImageView* picture_;
  QLabel* picture_info_;
  ReadingsEditor* legs_;
  QLabel* readings_hint_;
  QProgressBar* progress_;
  QLabel* status_;
  QPushButton* cancel_;
  QPlainTextEdit* report_;
  QString shown_status_;
  QString shown_legs_error_;  // legs.csv's error as the status line shows it, until it is fixed
  int pending_row_ = -1;      // picked while a detection ran
};

}  // namespace hexcal::ui

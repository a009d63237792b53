// Measure step: the session's images (load a folder; the Acquire step
// captures them pose by pose), the leg readings (enter in the table or
// import a CSV), each image with its detected tags and reprojected board, its
// status and RMS; the batch measurement into camera_poses.csv; camera
// intrinsics from a folder of target images, with their report.
// A points session (docs/session.md) has no images or camera: the panel then
// names its points and reflector files and lists each legs.csv pose with the
// fit of its points (ok, or why not: workflow/point_session.h), and the
// readings table is keyed by pose; the image and camera buttons are hidden.
//
//   auto* measure = new MeasurePanel(session);
//   measure->LoadImageFolder("/data/run1/images");
//   measure->MeasureAll();  // a worker: camera_poses.csv
#pragma once

#include <QWidget>
#include <map>
#include <optional>
#include <vector>

#include "ui/background_job.h"
#include "ui/qt_fwd.h"
#include "ui/readings_editor.h"
#include "ui/session_state.h"
#include "workflow/point_session.h"

namespace hexcal::ui {

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
  // The selected image's detection status, or the selected pose's fit status.
  const QString& ShownStatus() const { return shown_status_; }
  // A points session's description: its files, the reflectors, the fits.
  QString PointsSummary() const;

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
  // Points session or camera session: the widgets that make sense for it (measure_points.cc).
  void ShowInstrument();
  void LayOutButtons();  // the visible buttons, two a row
  void FillPoseList();   // each legs.csv pose and its fit, into the list
  void ShowPose(int row);
  bool CameraAndTargetReady(const QString& step);
  void ShowReadingsHint();  // how many images lack readings, after every refill
  std::map<QString, QString> ToMeasureAgain() const;  // image name: why its measurement is stale
  void StartJob(const QString& what, JobWork work);

  SessionState* session_;
  BackgroundJob* job_;      // measuring, capture, intrinsics: one at a time
  BackgroundJob* preview_;  // the selected image's detection
  QListWidget* images_;  // the images, or a points session's poses
  QLabel* list_title_;
  QLabel* points_summary_;  // a points session's files and reflectors
  QSplitter* top_;          // the list | the image (a points session: the summary)
  QGridLayout* buttons_;
  std::vector<QPushButton*> all_buttons_;     // in their order
  std::vector<QPushButton*> camera_buttons_;  // hidden in a points session
  std::optional<bool> arranged_for_points_;   // what ShowInstrument last arranged the widgets for
  QPushButton* import_legs_;
  std::vector<workflow::PointPoseFit> fits_;  // the poses listed, in a points session
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

#include "ui/measure_panel.h"

#include <QFileInfo>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>
#include <filesystem>
#include <map>

#include "core/csv.h"
#include "ui/background_job.h"
#include "ui/error_dialog.h"
#include "ui/gui_terms.h"
#include "ui/image_overlay.h"
#include "ui/image_view.h"
#include "ui/quantity_format.h"
#include "ui/text_wrap.h"
#include "vision/measure.h"
#include "workflow/measure_step.h"
#include "workflow/session_measure.h"

namespace hexcal::ui {
namespace {

QString Message(const Status& status) { return QString::fromStdString(status.message()); }

// camera_poses.csv by file name: "ok 0.21 px" or the status.
std::map<QString, QString> MeasuredStatus(const SessionPaths& paths) {
  std::map<QString, QString> status;
  StatusOr<CsvTable> table = ReadCsv(paths.camera_poses);
  if (!table.ok()) return status;
  for (const auto& row : table->rows)
    if (row.size() >= 16)
      status[QString::fromStdString(row[0])] =
          QString::fromStdString(row[15]) + ", RMS " + FormatPixels(QString::fromStdString(row[13]).toDouble());
  return status;
}

}  // namespace

MeasurePanel::MeasurePanel(SessionState* session, QWidget* parent)
    : QWidget(parent), session_(session), job_(new BackgroundJob(this)), preview_(new BackgroundJob(this)) {
  images_ = new QListWidget;
  images_->setObjectName("image_list");
  // File names are shown as they are, never as HTML.
  picture_ = new ImageView;
  picture_->setObjectName("image_view");
  picture_->SetMessage("Select an image to see its detection.");
  picture_info_ = new QLabel;
  picture_info_->setTextFormat(Qt::PlainText);
  picture_info_->setObjectName("image_status");
  picture_info_->setWordWrap(true);
  legs_ = new ReadingsEditor(session_);
  readings_hint_ = new QLabel;
  readings_hint_->setTextFormat(Qt::PlainText);
  readings_hint_->setWordWrap(true);
  readings_hint_->setObjectName("readings_hint");
  progress_ = new QProgressBar;
  status_ = new QLabel;
  status_->setTextFormat(Qt::PlainText);
  status_->setWordWrap(true);
  status_->setObjectName("measure_status");
  report_ = new QPlainTextEdit;
  report_->setReadOnly(true);
  report_->setObjectName("intrinsics_report");
  report_->setPlaceholderText("Intrinsics report");
  report_->setMaximumHeight(140);
  report_->setVisible(false);  // shown with an intrinsics report: room for the image until then

  list_title_ = new QLabel("Images (status from camera_poses.csv)");
  points_summary_ = new QLabel;
  points_summary_->setTextFormat(Qt::PlainText);
  points_summary_->setWordWrap(true);
  points_summary_->setObjectName("points_summary");
  points_summary_->setVisible(false);
  // Two buttons a row: one a row left the image list two rows at 1024×600.
  buttons_ = new QGridLayout;
  QGridLayout* buttons = buttons_;
  const auto add_button = [&](const QString& text, const QString& tip, auto slot) {
    auto* button = new QPushButton(text);
    button->setToolTip(tip);
    connect(button, &QPushButton::clicked, this, slot);
    buttons->addWidget(button, buttons->count() / 2, buttons->count() % 2);
    all_buttons_.push_back(button);
    return button;
  };
  camera_buttons_.push_back(add_button("Load image folder…",
                                       "Copy the PNG/JPEG/TIFF images of a folder into the session's images/",
                                       [this] { LoadImageFolder(); }));
  import_legs_ = add_button("Import leg readings…", "Use a CSV image,L1..L6[,holdout] as the session's legs.csv",
                            [this] { ImportLegs(); });
  camera_buttons_.push_back(add_button("Measure all images",
                                       "Detect the target in every image and write camera_poses.csv",
                                       [this] { MeasureAll(); }));
  camera_buttons_.push_back(add_button("Intrinsics from folder…",
                                       "Calibrate the camera from target images; the session then uses camera.yaml",
                                       [this] { IntrinsicsFromFolder(); }));
  cancel_ = add_button("Cancel", "Stop the running job", [this] { job_->Cancel(); });
  camera_buttons_.push_back(cancel_);  // a points session runs no job here
  cancel_->setEnabled(false);
  connect(job_, &BackgroundJob::Started, this, [this](const QString& what) {
    cancel_->setEnabled(true);
    status_->setText(what + "…");
  });
  connect(job_, &BackgroundJob::Finished, this, [this] { cancel_->setEnabled(false); });
  ShowProgressOn(job_, progress_);
  connect(images_, &QListWidget::currentRowChanged, this, &MeasurePanel::ShowImage);
  connect(preview_, &BackgroundJob::Finished, this, [this] {
    if (pending_row_ < 0) return;
    const int row = pending_row_;
    pending_row_ = -1;
    ShowImage(row);
  });
  connect(legs_, &ReadingsEditor::Note, this, [this](const QString& note) { status_->setText(Breakable(note)); });
  connect(legs_, &ReadingsEditor::Refilled, this, &MeasurePanel::ShowReadingsHint);

  ArrangeWidgets(buttons);
  connect(session_, &SessionState::Switched, this, &MeasurePanel::ResetForSession);
  connect(session_, &SessionState::Changed, this, &MeasurePanel::Refresh);
}

// The image list and its buttons left of the image, the readings below.
void MeasurePanel::ArrangeWidgets(QLayout* buttons) {
  auto* left = new QWidget;
  auto* left_layout = new QVBoxLayout(left);
  left_layout->addWidget(list_title_);
  left_layout->addWidget(images_, 1);
  left_layout->addLayout(buttons);
  left_layout->addWidget(progress_);
  left_layout->addWidget(status_);
  auto* centre = new QWidget;
  auto* centre_layout = new QVBoxLayout(centre);
  centre_layout->addWidget(points_summary_);
  centre_layout->addWidget(picture_, 1);
  centre_layout->addWidget(picture_info_);
  centre_layout->addWidget(report_);
  centre_layout->addStretch();  // the labels at the top when there is no image (a points session)
  auto* top = top_ = new QSplitter;
  top->addWidget(left);
  top->addWidget(centre);
  top->setStretchFactor(1, 3);
  // The image gets the width a long status line would take (the label's preferred width).
  top->setSizes({320, 700});
  auto* vertical = new QSplitter(Qt::Vertical);
  vertical->addWidget(top);
  auto* readings = new QWidget;
  auto* readings_layout = new QVBoxLayout(readings);
  readings_layout->setContentsMargins(0, 0, 0, 0);
  readings_layout->addWidget(readings_hint_);
  readings_layout->addWidget(legs_, 1);
  vertical->addWidget(readings);
  vertical->setStretchFactor(0, 3);
  vertical->setSizes({360, 200});  // the image list's rows and the buttons first; five rows of readings
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(vertical);
}

void MeasurePanel::ResetForSession() {
  job_->Abandon();
  preview_->Abandon();
  pending_row_ = -1;
  shown_status_.clear();
  shown_legs_error_.clear();
  picture_->SetMessage("Select an image to see its detection.");
  picture_info_->clear();
  status_->clear();
  report_->clear();
  report_->setVisible(false);
  progress_->reset();
  images_->clear();  // Refresh then shows the new session's first image
}

void MeasurePanel::Refresh() {
  ShowInstrument();
  const int current = images_->currentRow();
  const std::map<QString, QString> measured = MeasuredStatus(session_->Paths());
  const std::map<QString, QString> again = ToMeasureAgain();
  images_->blockSignals(true);
  images_->clear();
  for (const QString& file : session_->ImageFiles()) {
    const QString name = QFileInfo(file).fileName();
    const auto found = measured.find(name);
    const auto stale = again.find(name);
    // A row measured with another camera, target or image is no "ok" now.
    const QString state = found == measured.end() ? "not measured"
                          : stale != again.end()  ? "to measure again"
                                                  : found->second;
    auto* item = new QListWidgetItem(name + "  —  " + state);
    item->setData(Qt::UserRole, file);
    if (stale != again.end()) item->setToolTip(QString("Measured as %1, but %2.").arg(found->second, stale->second));
    if (found != measured.end())
      item->setForeground(stale != again.end()             ? QColor(200, 110, 0)
                          : found->second.startsWith("ok") ? QColor(Qt::darkGreen)
                                                           : QColor(Qt::red));
    images_->addItem(item);
  }
  if (session_->IsPointsSession()) FillPoseList();
  images_->blockSignals(false);
  // Keep the selection; show the first image when there was none.
  if (images_->count() > 0) images_->setCurrentRow(current >= 0 && current < images_->count() ? current : 0);
  // legs.csv's error while, and only while, it holds (issue 40): fixed on
  // disk, its line goes; the line of a job or an edit since is left alone.
  QString legs_error = InGuiTerms(session_->InSession(session_->LegsError()));  // the GUI's controls
  if (!legs_error.isEmpty() && !legs_error.startsWith("legs.csv")) legs_error = "legs.csv: " + legs_error;
  if (!legs_error.isEmpty()) {
    status_->setText(Breakable(legs_error));
  } else if (!shown_legs_error_.isEmpty() && status_->text() == Breakable(shown_legs_error_)) {
    status_->clear();
  }
  shown_legs_error_ = legs_error;
  legs_->Refill();
}

// The measured images whose row no longer holds (session_measure.h: the
// camera, the target or the image changed since), with the reason. None when
// the Measure step is done or nothing is measured: hashing every image is then
// not needed. (Not only when it is stale: with legs.csv broken the step is
// "to do", and the rows were still measured with the old camera.)
std::map<QString, QString> MeasurePanel::ToMeasureAgain() const {
  std::map<QString, QString> again;
  if (!session_->IsOpen() || session_->State(Step::kMeasure) == StepState::kDone ||
      !QFileInfo::exists(QString::fromStdString(session_->Paths().camera_poses)))
    return again;
  std::vector<std::string> images;
  for (const QString& file : session_->ImageFiles()) images.push_back(QFileInfo(file).fileName().toStdString());
  StatusOr<workflow::MeasureState> state = workflow::SessionMeasureState(session_->Dir().toStdString(), images);
  if (!state.ok() || state->reason.empty()) return again;
  // "2 image(s) changed since they were measured" is, for each of them:
  const QString reason = QString::fromStdString(state->reason).endsWith("image(s) changed since they were measured")
                             ? "the image changed since it was measured"
                             : QString::fromStdString(state->reason);
  for (const std::string& image : state->to_measure) again[QString::fromStdString(image)] = reason;
  return again;
}

void MeasurePanel::ShowReadingsHint() {
  const int missing = legs_->MissingRows();
  const QString unit = LengthUnitName(session_->NominalRobot().length_unit);
  const QString noun = session_->RowNoun();
  readings_hint_->setText(missing == 0 ? QString("Leg readings (robot unit, %1) of each %2:").arg(unit, noun)
                                       : QString("%1 %2(s) have no readings yet: type L1..L6 (%3) in their rows, "
                                                 "or paste lines of six numbers with Ctrl+V.")
                                             .arg(missing)
                                             .arg(noun, unit));
}

void MeasurePanel::StartJob(const QString& what, JobWork work) {
  if (!job_->Start(what, std::move(work)))
    ShowError(this, what, "Another job is running: wait for it, or press Cancel.");
}

bool MeasurePanel::CameraAndTargetReady(const QString& step) {
  if (!session_->IsOpen()) return ShowError(this, step, "Open or create a session first (File menu)."), false;
  if (session_->IsPointsSession()) {
    ShowError(this, step, "A points session has no images or camera: its poses come from the points file.");
    return false;
  }
  if (!session_->SessionCamera() || !session_->SessionTarget()) {
    ShowError(this, step,
              "The session's camera or target does not load: fix 'camera:' and 'target:' in session.yaml, "
              "or calibrate the intrinsics from a folder of target images.");
    return false;
  }
  return true;
}

void MeasurePanel::ShowImage(int row) {
  if (session_->IsPointsSession()) return ShowPose(row);
  if (row < 0 || row >= images_->count() || !CameraAndTargetReady("Show image")) return;
  if (preview_->Running()) {
    pending_row_ = row;
    return;
  }
  const QString file = images_->item(row)->data(Qt::UserRole).toString();
  picture_info_->setText(Breakable("detecting " + QFileInfo(file).fileName() + "…"));
  const Camera camera = *session_->SessionCamera();
  const Target target = *session_->SessionTarget();
  preview_->Start("detecting", [this, file, camera, target](const JobContext&) -> GuiContinuation {
    OverlayResult overlay = DetectAndDraw(file, camera, target);
    return [this, file, overlay] {
      picture_->SetImage(overlay.image);
      shown_status_ = overlay.status;
      picture_info_->setText(Breakable(QString("%1: %2 — %3 target tags, reprojection RMS %4  "
                                               "(green: detected tags and ids; red: the board reprojected)")
                                           .arg(QFileInfo(file).fileName(), overlay.status)
                                           .arg(overlay.tags)
                                           .arg(FormatPixels(overlay.rms_px))));
    };
  });
}

void MeasurePanel::MeasureAll() {
  if (!CameraAndTargetReady("Measure")) return;
  std::vector<std::string> files;
  for (const QString& file : session_->ImageFiles()) files.push_back(file.toStdString());
  if (files.empty()) return ShowError(this, "Measure", "images/ is empty: load an image folder or capture images.");
  // Every image again, under the session lock, with a record of the camera
  // and target it was measured with (workflow/session_measure.h).
  const workflow::MeasureFolderRequest request{session_->Dir().toStdString(), /*all=*/true, LockWait::kBriefly};
  StartJob("measuring", [this, files, request](const JobContext& context) -> GuiContinuation {
    StatusOr<workflow::SessionMeasurements> measured = workflow::MeasureSessionFolder(request, context);
    const Status written = measured.ok() ? Status::Ok() : measured.status();
    int usable = 0;
    if (measured.ok())
      for (const auto& [image, pose] : measured->poses) usable += pose.ok;
    return [this, written, usable, total = files.size()] {
      if (written.cancelled()) {
        status_->setText("measuring cancelled: camera_poses.csv is unchanged.");
      } else if (!written.ok()) {
        status_->setText("measuring failed.");
        ShowError(this, "Measure", Message(written));
      } else {
        status_->setText(QString("measured %1 images, %2 with a usable target pose.").arg(total).arg(usable));
      }
      session_->Reload();
    };
  });
}

}  // namespace hexcal::ui

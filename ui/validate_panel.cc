#include "ui/validate_panel.h"

#include <QChartView>
#include <QFile>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QTableWidget>
#include <QVBoxLayout>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/commands/command_table.h"
#include "charts/figures.h"
#include "ui/charts.h"
#include "ui/error_dialog.h"

namespace hexcal::ui {
namespace {

namespace fs = std::filesystem;

double Value(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

}  // namespace

ValidatePanel::ValidatePanel(SessionState* session, QWidget* parent) : QWidget(parent), session_(session) {
  status_ = new QLabel;
  status_->setWordWrap(true);
  status_->setObjectName("validate_status");
  summary_ = new QTableWidget(4, 2);
  summary_->setObjectName("validation_summary");
  summary_->setHorizontalHeaderLabels({"nominal robot (before)", "calibrated robot (after)"});
  summary_->setVerticalHeaderLabels({"position RMS", "position max", "orientation RMS (°)", "orientation max (°)"});
  summary_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  summary_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  summary_->setMaximumHeight(160);
  position_chart_ = MakeChartView(charts::ValidationPerImageChart({}, charts::ValidationQuantity::kPosition, ""));
  orientation_chart_ = MakeChartView(charts::ValidationPerImageChart({}, charts::ValidationQuantity::kOrientation, ""));
  auto* export_robot = new QPushButton("Export calibrated robot…");
  auto* export_report = new QPushButton("Export HTML report…");
  connect(export_robot, &QPushButton::clicked, this, [this] { ExportCalibratedRobot(); });
  connect(export_report, &QPushButton::clicked, this, [this] { ExportHtmlReport(); });
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(export_robot);
  buttons->addWidget(export_report);
  buttons->addStretch();
  auto* charts = new QHBoxLayout;
  charts->addWidget(position_chart_);
  charts->addWidget(orientation_chart_);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(status_);
  layout->addWidget(summary_);
  layout->addLayout(charts, 1);
  layout->addLayout(buttons);
  connect(session_, &SessionState::Changed, this, &ValidatePanel::Refresh);
}

void ValidatePanel::Refresh() {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 2; ++c) summary_->setItem(r, c, new QTableWidgetItem("—"));
  std::ifstream file((fs::path(session_->Paths().results) / "report.json").string());
  const nlohmann::json report = nlohmann::json::parse(file, nullptr, false);
  if (!report.is_object()) {
    status_->setText("No results yet: run the Calibrate step.");
    ShowChart(position_chart_, charts::ValidationPerImageChart({}, charts::ValidationQuantity::kPosition, ""));
    ShowChart(orientation_chart_, charts::ValidationPerImageChart({}, charts::ValidationQuantity::kOrientation, ""));
    return;
  }
  const nlohmann::json& validation = report["validation"];
  if (!validation.is_object()) {
    status_->setText(
        "No image was held out (holdout column of legs.csv), so there is nothing to validate on. "
        "Mark some images with holdout 1 in the Measure step and calibrate again.");
    return;
  }
  const QString unit = QString::fromStdString(report.value("length_unit", ""));
  status_->setText(QString("%1 held-out images: forward kinematics from their readings against the camera's pose, "
                           "lengths in %2. Rows where FK did not converge: before %3, after %4.")
                       .arg(validation.value("rows", 0))
                       .arg(unit)
                       .arg(validation["before"].value("failed", 0))
                       .arg(validation["after"].value("failed", 0)));
  const char* keys[] = {"position_rms", "position_max", "orientation_rms", "orientation_max"};
  for (int r = 0; r < 4; ++r) {
    summary_->setItem(r, 0, new QTableWidgetItem(QString::number(Value(validation["before"], keys[r]), 'g', 4)));
    summary_->setItem(r, 1, new QTableWidgetItem(QString::number(Value(validation["after"], keys[r]), 'g', 4)));
  }
  std::vector<charts::ImageValidation> images;
  for (const nlohmann::json& row : validation["per_image"]) {
    // The number in the image name fits under a bar.
    const QString name = QString::fromStdString(row.value("image", "")).section('.', 0, 0);
    const QRegularExpressionMatch number = QRegularExpression("(\\d+)$").match(name);
    images.push_back({(number.hasMatch() ? number.captured(1) : name).toStdString(),
                      {Value(row, "position_before"), Value(row, "position_after"), Value(row, "orientation_before"),
                       Value(row, "orientation_after")}});
  }
  const std::string length_unit = unit.toStdString();
  ShowChart(position_chart_,
            charts::ValidationPerImageChart(images, charts::ValidationQuantity::kPosition, length_unit));
  ShowChart(orientation_chart_,
            charts::ValidationPerImageChart(images, charts::ValidationQuantity::kOrientation, length_unit));
}

void ValidatePanel::ExportCalibratedRobot(const QString& chosen) {
  const QString source = QString::fromStdString((fs::path(session_->Paths().results) / "calibrated.yaml").string());
  if (!QFile::exists(source))
    return ShowError(this, "Export robot", "No calibrated robot yet: run the Calibrate step.");
  const QString path = chosen.isEmpty() ? QFileDialog::getSaveFileName(this, "Export calibrated robot",
                                                                       "calibrated.yaml", "YAML (*.yaml)")
                                        : chosen;
  if (path.isEmpty()) return;
  QFile::remove(path);
  if (!QFile::copy(source, path)) ShowError(this, "Export robot", "Could not write " + path + ": check the folder.");
}

void ValidatePanel::ExportHtmlReport(const QString& chosen) {
  if (!session_->IsOpen()) return ShowError(this, "Export report", "Open a session first (File menu).");
  const QString path = chosen.isEmpty()
                           ? QFileDialog::getSaveFileName(this, "Export HTML report", "report.html", "HTML (*.html)")
                           : chosen;
  if (path.isEmpty()) return;
  // The same code as `hexcal report`, so the page is the CLI's.
  const std::string dir = session_->Dir().toStdString(), out = path.toStdString();
  const char* argv[] = {"hexcal", "report", "--session", dir.c_str(), "--out", out.c_str(), "--force"};
  if (cli::RunHexcal(7, argv) != 0)
    ShowError(this, "Export report", "hexcal report failed (see the terminal): run the Calibrate step first.");
}

}  // namespace hexcal::ui

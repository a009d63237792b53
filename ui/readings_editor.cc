#include "ui/readings_editor.h"

#include <QApplication>
#include <QClipboard>
#include <QHeaderView>
#include <QKeyEvent>
#include <QRegularExpression>
#include <algorithm>

#include "ui/error_dialog.h"
#include "ui/quantity_format.h"
#include "ui/table_cell.h"

namespace hexcal::ui {
namespace {

constexpr int kHoldoutColumn = 1 + kNumLegs;

QString ReadingText(const std::optional<double>& value) { return value ? FormatCoordinate(*value) : QString(); }

}  // namespace

ReadingsEditor::ReadingsEditor(SessionState* session, QWidget* parent)
    : QTableWidget(0, 2 + kNumLegs, parent), session_(session) {
  setObjectName("legs_table");
  setHorizontalHeaderLabels({"image", "L1", "L2", "L3", "L4", "L5", "L6", "holdout (0/1)"});
  horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  // The image column as wide as an acquired image's name (widen it for longer ones).
  horizontalHeader()->setSectionResizeMode(0, QHeaderView::Interactive);
  setColumnWidth(0, fontMetrics().horizontalAdvance("pose_0000.png") + 24);
  ShowKeyColumn();
  connect(this, &QTableWidget::cellChanged, this, &ReadingsEditor::OnCellEdited);
}

int ReadingsEditor::MissingRows() const {
  return static_cast<int>(std::count_if(rows_.begin(), rows_.end(), [](const auto& r) { return !r.recorded; }));
}

void ReadingsEditor::Refill() {
  // Refilling now would put the file's value into the open editor (the text
  // typed so far lost, Enter then committing theirs): wait until it closes.
  if (state() == QAbstractItemView::EditingState) {
    refill_pending_ = true;
    return;
  }
  refill_pending_ = false;
  filling_ = true;
  rows_.clear();
  if (session_->IsOpen()) {
    StatusOr<std::vector<workflow::ReadingsRow>> rows = workflow::ReadReadingsTable(session_->Dir().toStdString());
    if (rows.ok()) rows_ = *rows;
  }
  ShowKeyColumn();
  setRowCount(static_cast<int>(rows_.size()));
  for (int r = 0; r < rowCount(); ++r) {
    const workflow::ReadingsRow& row = rows_[r];
    QTableWidgetItem* image = TableCell(QString::fromStdString(row.image), false);
    if (!row.recorded) image->setToolTip("no readings yet: type L1..L6");
    if (!row.image_present)
      image->setToolTip(session_->IsPointsSession()
                            ? "legs.csv names this pose, but the points file has no points for it"
                            : "legs.csv names this image, but it is not in images/");
    image->setForeground(!row.recorded ? QColor(200, 110, 0) : row.image_present ? QColor(0, 0, 0) : QColor(190, 0, 0));
    setItem(r, 0, image);
    const auto typed = typed_.find(row.image);
    for (int i = 0; i < kNumLegs; ++i) {
      const std::optional<double> shown = row.recorded || typed == typed_.end() ? row.legs[i] : typed->second[i];
      setItem(r, 1 + i, TableCell(ReadingText(shown), true));
    }
    setItem(r, kHoldoutColumn, TableCell(row.holdout ? "1" : "0", true));
  }
  filling_ = false;
  emit Refilled();
}

void ReadingsEditor::OnCellEdited(int row, int column) {
  if (filling_ || column == 0 || row < 0 || row >= static_cast<int>(rows_.size())) return;
  bool number = false;
  const double value = item(row, column)->text().toDouble(&number);
  if (!number || (column == kHoldoutColumn && value != 0 && value != 1)) {
    Refill();
    return ShowError(this, "Leg readings",
                     column == kHoldoutColumn ? "holdout is 0 or 1." : "A reading is a number in the robot unit.");
  }
  const workflow::ReadingsRow shown = rows_[row];
  if (column != kHoldoutColumn) {
    // The stroke, and the commanded pose's IK length for an acquired image.
    const Status plausible = workflow::CheckTypedReading(Check(), shown.image, column - 1, value, shown.commanded);
    if (!plausible.ok()) return Refuse(plausible);
  }
  if (shown.recorded) return EditRecorded(shown, column, value);
  EditBlank(row, column, value);
}

// A recorded row: the one cell, checked against the value shown (a cell that
// was not a number is replaced as typed).
void ReadingsEditor::EditRecorded(const workflow::ReadingsRow& shown, int column, double value) {
  workflow::LegsEdit edit;
  bool force = false;
  if (column == kHoldoutColumn) {
    edit = workflow::LegsEdit::SetHoldout(shown.image, shown.holdout, value == 1);
  } else {
    const std::optional<double> seen = shown.legs[column - 1];
    force = !seen.has_value();
    edit = workflow::LegsEdit::SetReading(shown.image, column - 1, seen.value_or(0), value);
  }
  if (!ApplySessionEdit(this, "Leg readings",
                        [&](bool overwrite) { return session_->EditLegs(edit, overwrite || force); }))
    Refill();  // the table shows the file again
}

// A blank row: kept until all six readings are typed, then written whole.
void ReadingsEditor::EditBlank(int row, int column, double value) {
  const std::string image = rows_[row].image;
  if (column == kHoldoutColumn) return;  // written with the readings
  typed_[image][column - 1] = value;
  std::array<double, kNumLegs> legs{};
  for (int i = 0; i < kNumLegs; ++i) {
    if (!typed_[image][i]) {
      emit Note(QString("%1: %2 of 6 readings typed").arg(QString::fromStdString(image)).arg(i));
      return;
    }
    legs[i] = *typed_[image][i];
  }
  const bool holdout = item(row, kHoldoutColumn)->text() == "1";
  if (WriteRow(image, legs, holdout, false)) typed_.erase(image);
}

bool ReadingsEditor::WriteRow(const std::string& image, const std::array<double, kNumLegs>& legs, bool holdout,
                              bool overwrite) {
  LegsRow row;
  row.image = image;
  for (int i = 0; i < kNumLegs; ++i) row.legs[i] = legs[i];
  row.holdout = holdout;
  const bool written = ApplySessionEdit(this, "Leg readings", [&](bool again) {
    return session_->EditLegs(workflow::LegsEdit::SetRow(row), overwrite || again);
  });
  if (written) emit Note(QString("%1: readings saved to legs.csv").arg(QString::fromStdString(image)));
  return written;
}

int ReadingsEditor::PasteReadings(const QString& text, int first) {
  const QStringList lines = text.split(QRegularExpression("[\r\n]+"), Qt::SkipEmptyParts);
  int written = 0, row = std::max(first, 0);
  // Rows first, then writes: each write reloads the session and refills the table.
  std::vector<std::pair<workflow::ReadingsRow, std::array<double, kNumLegs>>> pasted;
  for (int k = 0; k < lines.size() && row < static_cast<int>(rows_.size()); ++k) {
    const std::optional<std::array<double, kNumLegs>> legs = workflow::ParseReadingsLine(lines[k].toStdString());
    if (!legs) {
      emit Note(QString("pasted line %1 is not six numbers: stopped there").arg(k + 1));
      break;
    }
    LegReadings readings;
    for (int i = 0; i < kNumLegs; ++i) readings[i] = (*legs)[i];
    const Status plausible =
        workflow::CheckTypedReadings(Check(), "pasted line " + std::to_string(k + 1) + " (" + rows_[row].image + ")",
                                     readings, rows_[row].commanded);
    if (!plausible.ok()) {
      emit Note(QString::fromStdString(plausible.message()) + ": stopped there");
      break;
    }
    pasted.push_back({rows_[row++], *legs});
  }
  for (const auto& [shown, legs] : pasted) written += WriteRow(shown.image, legs, shown.holdout, /*overwrite=*/true);
  if (written > 0)
    emit Note(QString("pasted the readings of %1 %2(s) into legs.csv").arg(written).arg(session_->RowNoun()));
  return written;
}

// legs.csv's key column: `pose` in a points session, `image` otherwise.
void ReadingsEditor::ShowKeyColumn() {
  const QString noun = session_->RowNoun();
  horizontalHeaderItem(0)->setText(noun);
  setToolTip(QString("Leg readings at each %1 (robot unit): type them, or paste lines of six numbers with Ctrl+V. "
                     "legs.csv is saved at once. holdout 1 keeps the %1 out of the calibration to validate it.")
                 .arg(noun));
}

workflow::ReadingCheck ReadingsEditor::Check() const {
  return workflow::MakeReadingCheck(session_->NominalRobot(), session_->Config().noise);
}

// A reading beyond its stroke is not written: the table shows the file again
// and the operator is told which value, in which row, was refused.
void ReadingsEditor::Refuse(const Status& why) {
  Refill();
  const QString message = QString::fromStdString(why.message());
  emit Note(message);
  ShowError(this, "Leg readings", message);
}

void ReadingsEditor::closeEditor(QWidget* editor, QAbstractItemDelegate::EndEditHint hint) {
  QTableWidget::closeEditor(editor, hint);
  if (refill_pending_) Refill();  // after the commit, which was checked against the rows shown
}

void ReadingsEditor::keyPressEvent(QKeyEvent* event) {
  if (event->matches(QKeySequence::Paste)) {
    PasteReadings(QApplication::clipboard()->text(), currentRow());
    return;
  }
  QTableWidget::keyPressEvent(event);
}

}  // namespace hexcal::ui

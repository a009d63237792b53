// The leg readings table of the Measure and Acquire steps: one row per image
// (per pose in a points session, its column `pose`), L1..L6 in the robot unit
// and the holdout flag. Rows come from
// workflow::ReadReadingsTable, so an image without readings has a blank row to
// type into; its row enters legs.csv when the sixth reading is typed. Ctrl+V
// pastes lines of six numbers (a spreadsheet's rows) from the current row on.
// A reading outside its leg's stroke, or, for an image the Acquire step
// captured, far from the IK length of the pose it was commanded to, is
// refused, naming the image, the leg and the value (workflow::CheckTypedReading).
// Every change goes to legs.csv at once, as it is on disk (session_edits.h).
// A reload while a cell is being edited leaves the editor and its text alone:
// the table is refilled when the editor closes, and the typed value is
// applied against the value shown when typing began, so a change of the same
// cell on disk meanwhile asks Use mine / Keep theirs (issue 35).
//
//   auto* legs = new ReadingsEditor(session);
//   legs->PasteReadings("3.1 3.2 3.3 3.4 3.5 3.6\n", 0);  // row 0 into legs.csv
#pragma once

#include <QTableWidget>
#include <array>
#include <map>
#include <optional>
#include <vector>

#include "session/readings_table.h"
#include "ui/session_state.h"
#include "workflow/reading_check.h"

namespace hexcal::ui {

class ReadingsEditor : public QTableWidget {
  Q_OBJECT
 public:
  explicit ReadingsEditor(SessionState* session, QWidget* parent = nullptr);

  // Images shown without readings (blank rows).
  int MissingRows() const;
  // Pastes `text` (lines of six numbers) from row `first` on; returns the rows written.
  int PasteReadings(const QString& text, int first);

 public slots:
  void Refill();

 signals:
  // A sentence for the operator: what was written, or why not.
  void Note(const QString& text);
  // The rows shown are the file's again (MissingRows may have changed).
  void Refilled();

 protected:
  void keyPressEvent(QKeyEvent* event) override;
  void closeEditor(QWidget* editor, QAbstractItemDelegate::EndEditHint hint) override;

 private:
  void OnCellEdited(int row, int column);
  void EditRecorded(const workflow::ReadingsRow& shown, int column, double value);
  void EditBlank(int row, int column, double value);
  bool WriteRow(const std::string& image, const std::array<double, kNumLegs>& legs, bool holdout, bool overwrite);
  // The session's check of typed readings: its robot's strokes, its noise (workflow/reading_check.h).
  workflow::ReadingCheck Check() const;
  void Refuse(const Status& why);
  void ShowKeyColumn();  // the first column's name and the table's tooltip, by the session's kind

  SessionState* session_;
  std::vector<workflow::ReadingsRow> rows_;
  // Readings typed into a blank row, kept until its sixth arrives.
  std::map<std::string, std::array<std::optional<double>, kNumLegs>> typed_;
  bool filling_ = false;
  bool refill_pending_ = false;  // a reload came while a cell was being edited
};

}  // namespace hexcal::ui

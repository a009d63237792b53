// Table cells for the panels' QTableWidgets (the Acquire checklist, the
// plan, the readings): most cells show what hexcal computed or recorded and
// must not take the operator's typing, a few are the values they edit.
//
//   table->setItem(row, 0, TableCell(QString::number(row + 1)));      // read-only
//   table->setItem(row, 1, TableCell(ReadingText(value), true));      // editable
//   table->setItem(row, 2, SetEditable(new CoordinateItem(text), false));  // a sorting subclass
#pragma once

#include <QString>

class QTableWidgetItem;

namespace hexcal::ui {

// `item` made editable or not (Qt::ItemIsEditable); returned for setItem.
QTableWidgetItem* SetEditable(QTableWidgetItem* item, bool editable);
// A new cell showing `text`, read-only unless `editable`.
QTableWidgetItem* TableCell(const QString& text, bool editable = false);

}  // namespace hexcal::ui

#include "ui/table_cell.h"

#include <QTableWidgetItem>

namespace hexcal::ui {

QTableWidgetItem* SetEditable(QTableWidgetItem* item, bool editable) {
  item->setFlags(editable ? item->flags() | Qt::ItemIsEditable : item->flags() & ~Qt::ItemIsEditable);
  return item;
}

QTableWidgetItem* TableCell(const QString& text, bool editable) {
  return SetEditable(new QTableWidgetItem(text), editable);
}

}  // namespace hexcal::ui

#include "ui/step_list.h"

namespace hexcal::ui {

StepList::StepList(SessionState* session, QWidget* parent) : QListWidget(parent), session_(session) {
  setObjectName("step_list");
  for (int k = 0; k < kNumSteps; ++k) addItem(StepName(static_cast<Step>(k)));
  setMaximumWidth(190);
  QFont big = font();
  big.setPointSizeF(big.pointSizeF() * 1.2);
  setFont(big);
  setSpacing(4);
  connect(session_, &SessionState::Changed, this, &StepList::Refresh);
  Refresh();
}

void StepList::Refresh() {
  for (int k = 0; k < kNumSteps; ++k) {
    const Step step = static_cast<Step>(k);
    const StepState state = session_->State(step);
    QListWidgetItem* row = item(k);
    const char* mark = state == StepState::kDone ? "✓" : state == StepState::kStale ? "⟳" : "○";
    const char* what = state == StepState::kDone ? "done" : state == StepState::kStale ? "stale" : "to do";
    row->setText(QString("%1  %2").arg(mark, StepName(step)));
    row->setToolTip(QString("%1: %2").arg(StepName(step), what));
    row->setData(Qt::UserRole, static_cast<int>(state));
    row->setForeground(state == StepState::kDone    ? QColor(0, 120, 0)
                       : state == StepState::kStale ? QColor(200, 110, 0)
                                                    : QColor(90, 90, 90));
  }
}

}  // namespace hexcal::ui

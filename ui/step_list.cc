#include "ui/step_list.h"

#include "ui/gui_terms.h"

namespace hexcal::ui {

StepList::StepList(SessionState* session, QWidget* parent) : QListWidget(parent), session_(session) {
  setObjectName("step_list");
  for (int k = 0; k < kNumSteps; ++k) addItem(StepName(static_cast<Step>(k)));
  setFixedWidth(150);  // the same on every panel, and the most room for the panel at 1280 px
  QFont big = font();
  big.setPointSizeF(big.pointSizeF() * 1.2);
  setFont(big);
  setSpacing(4);
  connect(session_, &SessionState::Changed, this, &StepList::Refresh);
  Refresh();
}

namespace {

struct StateLook {
  const char* mark;
  const char* word;
  QColor colour;
};

StateLook LookOf(StepState state) {
  switch (state) {
    case StepState::kDone:
      return {"✓", "done", QColor(0, 120, 0)};
    case StepState::kStale:
      return {"⟳", "stale", QColor(200, 110, 0)};
    case StepState::kBroken:
      return {"✗", "broken", QColor(190, 0, 0)};
    case StepState::kTodo:
      break;
  }
  return {"○", "to do", QColor(90, 90, 90)};
}

}  // namespace

// The marks and the tooltips' sentences are those of `hexcal session status`,
// with the GUI's controls where it names the CLI's (ui/gui_terms.h).
void StepList::Refresh() {
  for (int k = 0; k < kNumSteps; ++k) {
    const Step step = static_cast<Step>(k);
    const StepState state = session_->State(step);
    const StateLook look = LookOf(state);
    QListWidgetItem* row = item(k);
    row->setText(QString("%1  %2").arg(look.mark, StepName(step)));
    row->setToolTip(QString("%1: %2 — %3").arg(StepName(step), look.word, InGuiTerms(session_->Why(step))));
    row->setData(Qt::UserRole, static_cast<int>(state));
    row->setForeground(look.colour);
  }
}

}  // namespace hexcal::ui

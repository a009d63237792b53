// The step list on the left of the main window: Robot, Plan, Measure,
// Calibrate, Validate, each marked done (✓), stale (⟳, an input changed since),
// broken (✗, a file that does not load) or to do (○), with the reason as its
// tooltip: the states of `hexcal session status`. Picking a step shows its panel.
//
//   auto* steps = new StepList(session);  // refreshes on SessionState::Changed
#pragma once

#include <QListWidget>

#include "ui/session_state.h"

namespace hexcal::ui {

class StepList : public QListWidget {
  Q_OBJECT
 public:
  StepList(SessionState* session, QWidget* parent = nullptr);

 public slots:
  void Refresh();

 private:
  SessionState* session_;
};

}  // namespace hexcal::ui

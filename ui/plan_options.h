// The planner's options as a form: one descriptor per option (key, label,
// unit, range, tooltip) makes the widget, reads it back and fills
// PlannerOptions, so an option is spelled once.
#pragma once

#include <QWidget>
#include <map>
#include <string>

#include "core/ioops.h"

class QComboBox;
class QCheckBox;
class QDoubleSpinBox;

namespace hexcal::ui {

// What the Plan panel hands to the worker: planner options plus how the
// candidate pool and the initial set are made (as `hexcal plan` does).
struct PlanJobOptions {
  PlannerOptions planner;
  std::string candidate_kind = "random";  // random | uniform | boundary
  int candidate_count = 2000;             // poses per random/uniform set
  std::string init = "random";            // random | uniform | boundary
};

class PlanOptionsForm : public QWidget {
  Q_OBJECT
 public:
  explicit PlanOptionsForm(QWidget* parent = nullptr);
  // Reads the form; the message names the option and says what to change.
  StatusOr<PlanJobOptions> Options() const;
  // Sets one numeric option by key (tests, presets): "poses", "candidate_count", ...
  void SetValue(const std::string& key, double value);

 private:
  std::map<std::string, QDoubleSpinBox*> numbers_;
  QComboBox *criterion_, *secondary_, *candidate_kind_, *init_;
  QCheckBox* continuous_;
};

}  // namespace hexcal::ui

// The Plan panel's options form: every row comes from
// workflow::PlanSetupOptions() (ui/option_form.h), the table that also makes
// the `hexcal plan` flags and the settings file's `planner:` section.
//
//   auto* form = new PlanOptionsForm;
//   form->SetValue("poses", 24);
//   StatusOr<workflow::PlanSetup> setup = form->Options();  // checked as the CLI checks
#pragma once

#include <QWidget>
#include <string>

#include "ui/option_form.h"
#include "workflow/plan_options.h"

namespace hexcal::ui {

class PlanOptionsForm : public QWidget {
  Q_OBJECT
 public:
  explicit PlanOptionsForm(QWidget* parent = nullptr);
  // Reads the form; the message names the option and says what to change.
  StatusOr<workflow::PlanSetup> Options() const;
  // Sets one option by key (tests, presets): "poses", "candidate_count", ...
  void SetValue(const std::string& key, double value);
  void SetText(const std::string& key, const std::string& text);
  // Every option back to its default (a new session).
  void Reset();

 private:
  OptionRows rows_;
  workflow::PlanSetup defaults_;
};

}  // namespace hexcal::ui

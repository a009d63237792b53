#include "ui/plan_options.h"

#include <QFormLayout>

#include "core/csv.h"

namespace hexcal::ui {

PlanOptionsForm::PlanOptionsForm(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  // As `hexcal plan`, except a smaller candidate set so that a first run on
  // the workstation takes seconds.
  defaults_.candidate_count = 2000;
  rows_ = AddOptionRows(form, workflow::PlanSetupOptions(), defaults_);
}

void PlanOptionsForm::Reset() {
  for (const OptionSpec<workflow::PlanSetup>& spec : workflow::PlanSetupOptions())
    if (const auto row = rows_.find(spec.key); row != rows_.end()) row->second.set_text(OptionText(spec, defaults_));
}

void PlanOptionsForm::SetValue(const std::string& key, double value) { SetText(key, FormatNumber(value)); }

void PlanOptionsForm::SetText(const std::string& key, const std::string& text) { rows_.at(key).set_text(text); }

StatusOr<workflow::PlanSetup> PlanOptionsForm::Options() const {
  StatusOr<workflow::PlanSetup> setup = ReadOptionRows(workflow::PlanSetupOptions(), rows_);
  if (!setup.ok()) return setup.status();
  if (setup->planner.criterion_switch_probability > 0 && !setup->planner.secondary)
    return Status::BadInput("Criterion switch needs a Secondary criterion: choose one, or set the switch to 0");
  if (Status s = setup->Check(); !s.ok()) return s;
  return setup;
}

}  // namespace hexcal::ui

#include "ui/plan_options.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>

namespace hexcal::ui {
namespace {

struct NumberOption {
  const char* key;
  const char* label;
  const char* unit;
  double min, max, value;
  int decimals;
  const char* tooltip;
};

// Defaults as `hexcal plan` (docs/planner.md), except a smaller candidate set
// so that a first run on the workstation takes seconds.
const NumberOption kNumberOptions[] = {
    {"poses", "Poses N", "poses", 7, 500, 18, 0, "Number of poses in the plan (paper: 18 to 36)."},
    {"candidate_count", "Candidates", "poses", 50, 100000, 2000, 0,
     "Poses in the random or uniform candidate set AddFind searches (feasible poses only)."},
    {"keep", "Keep on primary", "fraction", 0.05, 1, 0.8, 2,
     "Section 6.2: fraction of the AddFind results kept on the primary criterion before the secondary picks."},
    {"tabu", "Tabu list n", "poses", 0, 100, 0, 0,
     "Section 4.3: the last n added poses may not be removed; 0 turns the Tabu search off."},
    {"iterations", "Iteration budget", "iterations", 0, 100000, 0, 0,
     "0: 200 with Tabu, else 10 N. The search also stops when the same pose is added and removed."},
    {"addfind_starts", "AddFind starts U", "candidates", 0, 100000, 0, 0,
     "Candidates drawn each iteration (0: all of them; continuous mode: 40 SLSQP starts)."},
    {"switch_probability", "Criterion switch", "probability", 0, 1, 0, 2,
     "Section 4.2: AddFind uses the secondary criterion with this probability."},
    {"removal_choices", "Removal choices r", "poses", 1, 50, 1, 0,
     "Section 4.2: RemoveFind drops one of the r least useful poses at random."},
    {"seed", "Seed", "", 0, 1e9, 1, 0, "Random seed of candidates, initial set and randomisation."},
    {"threads", "Scoring threads", "threads", 0, 64, 0, 0, "Threads that score candidates; 0: every core."},
};

QComboBox* Combo(const QStringList& items, const QString& tooltip) {
  auto* box = new QComboBox;
  box->addItems(items);
  box->setToolTip(tooltip);
  return box;
}

}  // namespace

PlanOptionsForm::PlanOptionsForm(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  const QStringList criteria = {"O1", "O2", "O3", "O4", "D", "A", "E"};
  criterion_ = Combo(criteria,
                     "Primary criterion of AddFind and RemoveFind (section 2): O1 maximises the product of "
                     "singular values (D-optimal), O2 the conditioning, O3 the smallest singular value, "
                     "O4 the noise amplification.");
  secondary_ = Combo(QStringList{"none"} + criteria,
                     "Section 6.2: secondary criterion that picks among the best "
                     "'keep' fraction of AddFind's results.");
  candidate_kind_ = Combo({"random", "uniform", "boundary"},
                          "Candidate poses: random or uniform (Halton) in the sampling box, or the section 6.1 "
                          "boundary poses (all 2⁶ stroke ends, every assembly mode).");
  init_ = Combo({"random", "uniform", "boundary"}, "How the N starting poses are drawn.");
  continuous_ = new QCheckBox;
  continuous_->setToolTip(
      "AddFind by constrained local maximisation (SLSQP) in the workspace; the candidates are "
      "only the starts.");
  criterion_->setObjectName("criterion");
  form->addRow("Criterion", criterion_);
  form->addRow("Secondary", secondary_);
  form->addRow("Candidate kind", candidate_kind_);
  form->addRow("Initial set", init_);
  form->addRow("Continuous AddFind", continuous_);
  for (const NumberOption& option : kNumberOptions) {
    auto* spin = new QDoubleSpinBox;
    spin->setObjectName(option.key);
    spin->setRange(option.min, option.max);
    spin->setDecimals(option.decimals);
    spin->setValue(option.value);
    if (option.unit[0]) spin->setSuffix(QString(" ") + option.unit);
    spin->setToolTip(option.tooltip);
    numbers_[option.key] = spin;
    auto* label = new QLabel(option.label);
    label->setToolTip(option.tooltip);
    form->addRow(label, spin);
  }
}

void PlanOptionsForm::SetValue(const std::string& key, double value) { numbers_.at(key)->setValue(value); }

StatusOr<PlanJobOptions> PlanOptionsForm::Options() const {
  PlanJobOptions options;
  const auto number = [this](const char* key) { return numbers_.at(key)->value(); };
  PlannerOptions& planner = options.planner;
  planner.num_poses = static_cast<int>(number("poses"));
  planner.criterion = *ParseCriterion(criterion_->currentText().toStdString());
  if (secondary_->currentIndex() > 0) planner.secondary = ParseCriterion(secondary_->currentText().toStdString());
  planner.keep = number("keep");
  planner.tabu = static_cast<int>(number("tabu"));
  planner.iterations = static_cast<int>(number("iterations"));
  planner.addfind_starts = static_cast<int>(number("addfind_starts"));
  planner.criterion_switch_probability = number("switch_probability");
  planner.removal_choices = static_cast<int>(number("removal_choices"));
  planner.seed = static_cast<uint64_t>(number("seed"));
  planner.threads = static_cast<int>(number("threads"));
  planner.continuous = continuous_->isChecked();
  options.candidate_kind = candidate_kind_->currentText().toStdString();
  options.candidate_count = static_cast<int>(number("candidate_count"));
  options.init = init_->currentText().toStdString();
  std::string error;
  if (!planner.IsValid(&error)) return Status::Error("planner options: " + error);
  if (planner.criterion_switch_probability > 0 && !planner.secondary)
    return Status::Error("Criterion switch needs a Secondary criterion: choose one, or set the switch to 0");
  return options;
}

}  // namespace hexcal::ui

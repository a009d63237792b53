#include "workflow/plan_options.h"

#include "core/candidates.h"

namespace hexcal::workflow {
namespace {

using Spec = OptionSpec<PlanSetup>;

std::vector<std::string> CriterionChoices(bool with_none) {
  std::vector<std::string> names;
  if (with_none) names.push_back("none");
  for (const auto& [name, criterion] : CriterionNames()) names.push_back(name);
  return names;
}

std::vector<std::string> CandidateKindChoices() {
  std::vector<std::string> names;
  for (const auto& [name, kind] : CandidateKindNames()) names.push_back(name);
  return names;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ",") + name;
  return text;
}

// A numeric option bound to one field of PlanSetup (or of its planner).
template <typename Field>
Spec Number(std::string key, std::string label, OptionType type, std::string unit, double min, double max,
            std::string help, Field field) {
  return NumberOption<PlanSetup>(std::move(key), std::move(label), type, std::move(unit), min, max, std::move(help),
                                 field);
}

// An option whose range is the planner's own rule (core/ioops.h), taken whole.
Spec Planner(const std::string& key) {
  return NestedOption<PlanSetup>(*FindOption(PlannerOptionSpecs(), key),
                                 [](PlanSetup& s) -> PlannerOptions& { return s.planner; });
}

void AddCriteria(OptionTable<PlanSetup>* t) {
  t->push_back(ChoiceOption<PlanSetup>(
      "criterion", "Criterion", OptionType::kChoice, CriterionChoices(false),
      "primary criterion of AddFind and RemoveFind: S minimises the predicted mean parameter standard deviation "
      "(the default); section 2's O1 maximises the product of singular values (D-optimal), O2 the conditioning, "
      "O3 the smallest singular value, O4 the noise amplification",
      [](const PlanSetup& s) { return std::string(CriterionName(s.planner.criterion)); },
      [](PlanSetup& s, const std::string& v) { s.planner.criterion = *ParseCriterion(v); }));
  t->push_back(ChoiceOption<PlanSetup>(
      "secondary", "Secondary", OptionType::kChoice, CriterionChoices(true),
      "section 6.2: the criterion that picks among the best `keep` fraction of AddFind's results",
      [](const PlanSetup& s) {
        return s.planner.secondary ? CriterionName(*s.planner.secondary) : std::string("none");
      },
      [](PlanSetup& s, const std::string& v) {
        s.planner.secondary = v == "none" ? std::nullopt : ParseCriterion(v);
      }));
  t->push_back(Planner("keep"));
}

void AddSearch(OptionTable<PlanSetup>* t) {
  t->push_back(Planner("poses"));
  t->push_back(Planner("tabu"));
  t->push_back(Planner("iterations"));
  t->push_back(Planner("addfind_starts"));
  Spec continuous = Number("continuous", "Continuous AddFind", OptionType::kFlag, "", 0, 1,
                           "AddFind by SLSQP in the workspace; the candidates are only the starts",
                           [](PlanSetup& s) -> bool& { return s.planner.continuous; });
  t->push_back(continuous);
  t->push_back(Number("polish", "Continuous polish", OptionType::kInteger, "iterations", 0, 100000,
                      "continuous IOOPS iterations from the finite plan (SLSQP under every constraint); 0: none",
                      [](PlanSetup& s) -> int& { return s.polish; }));
  t->push_back(Planner("switch_probability"));
  t->push_back(Planner("removal_choices"));
}

void AddSources(OptionTable<PlanSetup>* t) {
  t->push_back(ChoiceOption<PlanSetup>(
      "candidate_kind", "Candidate kinds", OptionType::kChoiceList, CandidateKindChoices(),
      "generated candidate sets, pooled: random or uniform (Halton) in the sampling box, boundary (section 6.1)",
      [](const PlanSetup& s) { return JoinNames(s.candidate_kinds); },
      [](PlanSetup& s, const std::string& v) { s.candidate_kinds = SplitOptionList(v); }));
  t->push_back(Number("candidate_count", "Candidates", OptionType::kInteger, "poses", 0, 10000000,
                      "poses per random or uniform set (0: 10000, continuous 2000)",
                      [](PlanSetup& s) -> int& { return s.candidate_count; }));
  Spec init = ChoiceOption<PlanSetup>(
      "init", "Initial set", OptionType::kChoice, CandidateKindChoices(),
      "how the N starting poses are drawn, or a pose CSV file of N poses", [](const PlanSetup& s) { return s.init; },
      [](PlanSetup& s, const std::string& v) { s.init = v; });
  init.file_allowed = true;
  t->push_back(init);
  t->push_back(Planner("seed"));
  t->push_back(Planner("threads"));
  t->push_back(Number("certificate", "Optimality certificates", OptionType::kFlag, "", 0, 1,
                      "compute the D- and S-optimal design bounds on the candidates and the plan's efficiencies",
                      [](PlanSetup& s) -> bool& { return s.certificate; }));
  t->push_back(Number("certificate_seconds", "Certificate time limit", OptionType::kNumber, "s", 0.1, 86400,
                      "time limit of each design bound",
                      [](PlanSetup& s) -> double& { return s.certificate_seconds; }));
}

}  // namespace

PlannerOptions DefaultPlannerOptions() {
  PlannerOptions options;
  options.criterion = Criterion::kS;
  options.tabu = 4;
  return options;
}

Status PlanSetup::Check() const {
  if (Status s = planner.Check(); !s.ok()) return s;
  if (candidate_kinds.empty()) return Status::BadInput("candidate_kind: name at least one kind");
  return Status::Ok();
}

const OptionTable<PlanSetup>& PlanSetupOptions() {
  static const OptionTable<PlanSetup> table = [] {
    OptionTable<PlanSetup> t;
    AddSearch(&t);
    AddCriteria(&t);
    AddSources(&t);
    return t;
  }();
  return table;
}

}  // namespace hexcal::workflow

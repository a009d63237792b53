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
  t->push_back(Number("tabu", "Tabu list n", OptionType::kInteger, "poses", 0, 100000,
                      "section 4.3: the last n added poses may not be removed; 0 turns Tabu off",
                      [](PlanSetup& s) -> int& { return s.planner.tabu; }));
  t->push_back(Number("iterations", "Iteration budget", OptionType::kInteger, "iterations", 0, 1000000,
                      "0: 200 with Tabu, else 10 N; the search also stops when a pose is added and removed again",
                      [](PlanSetup& s) -> int& { return s.planner.iterations; }));
  t->push_back(Number("addfind_starts", "AddFind starts U", OptionType::kInteger, "candidates", 0, 10000000,
                      "candidates drawn each iteration (0: all of them; continuous: 40 SLSQP starts)",
                      [](PlanSetup& s) -> int& { return s.planner.addfind_starts; }));
  Spec continuous = Number("continuous", "Continuous AddFind", OptionType::kFlag, "", 0, 1,
                           "AddFind by SLSQP in the workspace; the candidates are only the starts",
                           [](PlanSetup& s) -> bool& { return s.planner.continuous; });
  t->push_back(continuous);
  t->push_back(Number("polish", "Continuous polish", OptionType::kInteger, "iterations", 0, 100000,
                      "continuous IOOPS iterations from the finite plan (SLSQP under every constraint); 0: none",
                      [](PlanSetup& s) -> int& { return s.polish; }));
  t->push_back(Number("switch_probability", "Criterion switch", OptionType::kNumber, "probability", 0, 1,
                      "section 4.2: AddFind uses the secondary criterion with this probability",
                      [](PlanSetup& s) -> double& { return s.planner.criterion_switch_probability; }));
  t->push_back(Number("removal_choices", "Removal choices r", OptionType::kInteger, "poses", 1, 1000,
                      "section 4.2: RemoveFind drops one of the r least useful poses at random",
                      [](PlanSetup& s) -> int& { return s.planner.removal_choices; }));
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
  t->push_back(SeedOption<PlanSetup>("random seed of the candidates, the initial set and the randomisation",
                                     [](PlanSetup& s) -> uint64_t& { return s.planner.seed; }));
  t->push_back(ThreadsOption<PlanSetup>("Scoring threads", "threads that score candidates; 0 = every core",
                                        [](PlanSetup& s) -> int& { return s.planner.threads; }));
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
  std::string error;
  if (!planner.IsValid(&error)) return Status::BadInput("planner options: " + error);
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

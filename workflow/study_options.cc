#include "workflow/study_options.h"

#include <limits>

#include "core/robot.h"

namespace hexcal::workflow {
namespace {

using Spec = OptionSpec<StudyRequest>;

// An integer (or, with kFlag, 0/1) option bound to one field of the request.
template <typename Field>
Spec Number(std::string key, std::string label, OptionType type, std::string unit, double min, double max,
            std::string help, Field field) {
  return NumberOption<StudyRequest>(std::move(key), std::move(label), type, std::move(unit), min, max,
                                    std::move(help), field);
}

std::vector<std::string> CriterionChoices(bool with_none) {
  std::vector<std::string> names;
  if (with_none) names.push_back("none");
  for (const auto& [name, criterion] : CriterionNames()) names.push_back(name);
  return names;
}

Spec CriterionOption() {
  Spec spec;
  spec.key = "criterion";
  spec.label = "Criterion";
  spec.type = OptionType::kChoice;
  spec.choices = CriterionChoices(false);
  spec.help = "IOOPS's criterion for the selected subset (section 8 used O4; O1 with weighted rows validates better)";
  spec.get_choice = [](const StudyRequest& r) { return std::string(CriterionName(r.study.criterion)); };
  spec.set_choice = [](StudyRequest& r, const std::string& v) { r.study.criterion = *ParseCriterion(v); };
  return spec;
}

Spec SecondaryOption() {
  Spec spec;
  spec.key = "secondary";
  spec.label = "Secondary";
  spec.type = OptionType::kChoice;
  spec.choices = CriterionChoices(true);
  spec.help = "section 6.2's secondary criterion of IOOPS; none in section 8";
  spec.get_choice = [](const StudyRequest& r) {
    return r.study.secondary ? std::string(CriterionName(*r.study.secondary)) : std::string("none");
  };
  spec.set_choice = [](StudyRequest& r, const std::string& v) {
    r.study.secondary = v == "none" ? std::nullopt : ParseCriterion(v);
  };
  return spec;
}

// The flag is the exception, so the default (weighted rows) needs no flag.
Spec UnweightedOption() {
  Spec spec;
  spec.key = "unweighted_selection";
  spec.label = "Unweighted selection";
  spec.type = OptionType::kFlag;
  spec.help = "IOOPS on the paper's unweighted J_P instead of rows weighted by the session's noise model";
  spec.get_number = [](const StudyRequest& r) { return r.weighted_selection ? 0.0 : 1.0; };
  spec.set_number = [](StudyRequest& r, double v) { r.weighted_selection = v == 0; };
  return spec;
}

}  // namespace

const OptionTable<StudyRequest>& StudyOptions() {
  static const OptionTable<StudyRequest> table = [] {
    OptionTable<StudyRequest> t;
    t.push_back(Number("select", "Poses per subset (N)", OptionType::kInteger, "poses", kParamsPerLeg, 100000,
                       "poses in the selected and in each random subset (the paper's 13); fewer than the "
                       "session's measured poses",
                       [](StudyRequest& r) -> int& { return r.study.select; }));
    t.push_back(Number("subsets", "Random subsets (K)", OptionType::kInteger, "", 1, 1000000,
                       "random subsets of N poses the selected one is ranked against (the paper's 6000)",
                       [](StudyRequest& r) -> int& { return r.study.subsets; }));
    t.push_back(CriterionOption());
    t.push_back(SecondaryOption());
    t.push_back(Number("starts", "IOOPS starts", OptionType::kInteger, "", 1, 1000,
                       "IOOPS runs from this many random initial subsets; the best on the criterion is kept",
                       [](StudyRequest& r) -> int& { return r.study.selection_starts; }));
    t.push_back(UnweightedOption());
    t.push_back(Number("seed", "Seed", OptionType::kInteger, "", 0, 9007199254740992.0,
                       "seed of the IOOPS starts and the random subsets; the numbers do not depend on the threads",
                       [](StudyRequest& r) -> uint64_t& { return r.study.seed; }));
    t.push_back(Number("threads", "Threads", OptionType::kInteger, "threads", 0, 256,
                       "subsets calibrated at once; 0 = every core",
                       [](StudyRequest& r) -> int& { return r.study.num_threads; }));
    return t;
  }();
  return table;
}

}  // namespace hexcal::workflow

#include "workflow/study_options.h"

#include "core/robot.h"

namespace hexcal::workflow {
namespace {

using Spec = OptionSpec<StudyRequest>;

// An option whose range is the study's own rule (core/subset_study.h), taken whole.
Spec Study(const std::string& key) {
  return NestedOption<StudyRequest>(*FindOption(SubsetStudyOptionSpecs(), key),
                                    [](StudyRequest& r) -> SubsetStudyOptions& { return r.study; });
}

std::vector<std::string> CriterionChoices(bool with_none) {
  std::vector<std::string> names;
  if (with_none) names.push_back("none");
  for (const auto& [name, criterion] : CriterionNames()) names.push_back(name);
  return names;
}

Spec CriterionOption() {
  return ChoiceOption<StudyRequest>(
      "criterion", "Criterion", OptionType::kChoice, CriterionChoices(false),
      "IOOPS's criterion for the selected subset (section 8 used O4; O1 with weighted rows validates better)",
      [](const StudyRequest& r) { return std::string(CriterionName(r.study.criterion)); },
      [](StudyRequest& r, const std::string& v) { r.study.criterion = *ParseCriterion(v); });
}

Spec SecondaryOption() {
  return ChoiceOption<StudyRequest>(
      "secondary", "Secondary", OptionType::kChoice, CriterionChoices(true),
      "section 6.2's secondary criterion of IOOPS; none in section 8",
      [](const StudyRequest& r) {
        return r.study.secondary ? std::string(CriterionName(*r.study.secondary)) : std::string("none");
      },
      [](StudyRequest& r, const std::string& v) {
        r.study.secondary = v == "none" ? std::nullopt : ParseCriterion(v);
      });
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
    t.push_back(Study("select"));
    t.push_back(Study("subsets"));
    t.push_back(CriterionOption());
    t.push_back(SecondaryOption());
    t.push_back(Study("starts"));
    t.push_back(UnweightedOption());
    t.push_back(Study("seed"));
    t.push_back(Study("threads"));
    return t;
  }();
  return table;
}

}  // namespace hexcal::workflow

// Each option's rule is written once, in its descriptor (issue 37): the CLI
// flag made from the table refuses a value out of range with the same words
// as the lower layer's own check of the struct, which names the option by its
// key for the CLI to show as the flag. And docs/cli.md carries each table as
// the code generates it.
#include "app/commands/option_flags.h"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/calibration.h"
#include "core/noise_model.h"
#include "tests/test_support.h"
#include "vision/target_print.h"
#include "workflow/acquire_step.h"
#include "workflow/demo_options.h"
#include "workflow/simulate_options.h"
#include "workflow/simulate_step.h"
#include "workflow/study_options.h"
#include "workflow/study_step.h"

namespace hexcal::cli {
namespace {

// CLI11's words when it refuses `flag value` of a command made from `table`; "" when it takes it.
template <typename T>
std::string FlagRefusal(const OptionTable<T>& table, const std::string& prefix, const std::string& flag,
                        const std::string& value) {
  CLI::App app;
  OptionFlagNames names;
  AddOptionFlags(&app, table, std::make_shared<OptionEntries>(), &names, prefix);
  const char* argv[] = {"hexcal", flag.c_str(), value.c_str()};
  try {
    app.parse(3, argv);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

// Every number option of `table`, just out of its range, is refused by its
// flag and by `check` (the struct's own check, or the step that runs it)
// with the same words, and the check names the option by its key.
template <typename T>
void ExpectOneRuleEverywhere(const OptionTable<T>& table, const std::function<Status(const T&)>& check,
                             const std::string& prefix = "") {
  CLI::App app;
  OptionFlagNames flags;
  AddOptionFlags(&app, table, std::make_shared<OptionEntries>(), &flags, prefix);
  int checked = 0;
  for (const OptionSpec<T>& spec : table) {
    if (spec.type != OptionType::kInteger && spec.type != OptionType::kNumber) continue;
    std::vector<double> outside;
    if (spec.max + 1 != spec.max) outside.push_back(spec.max + 1);  // 2^53 + 1 is 2^53 as a double
    // Below 0 is no value of an unsigned field (a seed).
    if (spec.type == OptionType::kNumber || spec.min != 0) outside.push_back(spec.min - 1);
    for (double value : outside) {
      T values{};
      spec.set_number(values, value);
      const Status lower = check(values);
      EXPECT_EQ(lower.kind(), StatusKind::kBadInput) << spec.key << " = " << value;
      EXPECT_EQ(lower.option(), spec.key) << lower.message();
      const std::string cli = FlagRefusal(table, prefix, flags.at(spec.key), FormatNumber(value));
      EXPECT_EQ(cli, InFlagWords(lower, flags).message()) << spec.key << " = " << value;
      EXPECT_EQ(cli.rfind(flags.at(spec.key) + ": must be at ", 0), 0u) << cli;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

void ExpectInDocs(const std::string& table) {
  const std::string docs = testing::ReadTextFile((testing::SourceDir() / "docs" / "cli.md").string());
  EXPECT_NE(docs.find(table), std::string::npos) << "docs/cli.md needs this table:\n" << table;
}

TEST(OptionFlags, ShowALowerLayersOptionAsTheFlag) {
  const OptionFlagNames flags = {{"settle", "--settle"}, {"position", "--noise-position"}};
  EXPECT_EQ(InFlagWords(Status::BadOption("position", "must be at least 0"), flags).message(),
            "--noise-position: must be at least 0");
  // A key the command has no flag for, and an error about no option, stay as they are.
  EXPECT_EQ(InFlagWords(Status::BadOption("select", "too many"), flags).message(), "select: too many");
  EXPECT_EQ(InFlagWords(Status::BadInput("settle: a file name"), flags).message(), "settle: a file name");
  const Status failed = Status::Failed("only 3 poses").AboutOption("settle");
  EXPECT_EQ(InFlagWords(failed, flags).message(), "--settle: only 3 poses");
  EXPECT_EQ(InFlagWords(failed, flags).kind(), StatusKind::kFailed);
}

TEST(OptionFlags, TheHelpShowsTheRangeAndTheDefault) {
  CLI::App app;
  OptionFlagNames flags;
  AddOptionFlags(&app, workflow::AcquireOptionSpecs(), std::make_shared<OptionEntries>(), &flags);
  const std::string help = app.help();
  EXPECT_NE(help.find("--settle NUMBER:NUMBER in [0, 600]"), std::string::npos) << help;
  EXPECT_NE(help.find("default: the controller's (sim 0, LinuxCNC 0.5)"), std::string::npos) << help;
  EXPECT_NE(help.find("--holdout-every INT:INT in [0, 1000000]=0"), std::string::npos) << help;
}

TEST(AcquireOptionSpecs, OneRuleForTheFlagsAndTheStep) {
  const auto acquire = [](const workflow::AcquireOptions& options) {
    workflow::AcquireRequest request{"no-such-session"};
    request.options = options;
    return workflow::AcquirePlan(request).status();
  };
  ExpectOneRuleEverywhere<workflow::AcquireOptions>(workflow::AcquireOptionSpecs(), acquire);
  // The rule no range says: the flag takes 1 (in range), the step refuses it in the flag's name.
  EXPECT_EQ(FlagRefusal(workflow::AcquireOptionSpecs(), "", "--holdout-every", "1"), "");
  workflow::AcquireOptions every_pose;
  every_pose.holdout_every = 1;
  const OptionFlagNames flags = {{"holdout_every", "--holdout-every"}};
  EXPECT_EQ(InFlagWords(acquire(every_pose), flags).message(),
            "--holdout-every: must be 0 (none) or at least 2, got 1 (every pose held out)");
  // Unset, the settle time is the controller's: no range to check.
  EXPECT_TRUE(workflow::AcquireOptions{}.Check().ok());
  ExpectInDocs(OptionsMarkdownTable(workflow::AcquireOptionSpecs()));
}

TEST(SimulateOptions, OneRuleForTheFlagsAndTheStep) {
  ExpectOneRuleEverywhere<workflow::SimulateRequest>(workflow::SimulateOptions(), [](workflow::SimulateRequest r) {
    r.robot = "inria-left-hand";
    return workflow::RunSimulationStudy(r).status();
  });
  // The core's own check, of the options it takes whole.
  ExpectOneRuleEverywhere<SimulationOptions>(SimulationOptionSpecs(),
                                             [](const SimulationOptions& o) { return o.Check(); });
  // The step's own checks of its text options name them by key.
  const OptionFlagNames flags = {{"sweep", "--sweep"}, {"random_box", "--random-box"}, {"sets", "--sets"}};
  workflow::SimulateRequest request;
  request.robot = "inria-left-hand";
  request.sweep = "8-41";
  EXPECT_EQ(InFlagWords(workflow::RunSimulationStudy(request).status(), flags).message(),
            "--sweep: '8-41' is not MIN:MAX with 7 <= MIN <= MAX <= 10000, e.g. 8:41");
  request.sweep = "";
  request.sets = "random,,boundary";
  EXPECT_EQ(InFlagWords(workflow::RunSimulationStudy(request).status(), flags).message(),
            "--sets: empty entry in 'random,,boundary'");
  request.sets = "random";
  request.random_box = "w:1:2";
  EXPECT_EQ(InFlagWords(workflow::RunSimulationStudy(request).status(), flags).message(),
            "--random-box: 'w:1:2' is not NAME:MIN:MAX (x, y, z, q1, q2, q3)");
  ExpectInDocs(OptionsMarkdownTable(workflow::SimulateOptions()));
}

TEST(DemoOptions, OneRuleForTheFlagsAndTheStep) {
  ExpectOneRuleEverywhere<workflow::DemoRequest>(
      workflow::DemoOptions(), [](const workflow::DemoRequest& r) { return workflow::RunDemo(r).status(); });
  ExpectInDocs(OptionsMarkdownTable(workflow::DemoOptions()));
}

TEST(StudyOptions, OneRuleForTheFlagsAndTheStep) {
  ExpectOneRuleEverywhere<workflow::StudyRequest>(workflow::StudyOptions(), [](workflow::StudyRequest r) {
    r.session = "no-such-session";
    return workflow::RunStudy(r).status();
  });
  ExpectOneRuleEverywhere<SubsetStudyOptions>(SubsetStudyOptionSpecs(),
                                              [](const SubsetStudyOptions& o) { return o.Check(); });
}

TEST(CalibrationOptionSpecs, OneRuleForTheFlagsAndIsValid) {
  // IsValid's message names the option by its key, as the flag check names the flag.
  ExpectOneRuleEverywhere<CalibrationOptions>(CalibrationOptionSpecs(), [](const CalibrationOptions& o) {
    std::string error;
    if (o.IsValid(&error)) return Status::Ok();
    const size_t colon = error.find(": ");
    return Status::BadOption(error.substr(0, colon), error.substr(colon + 2));
  });
  EXPECT_EQ(FlagRefusal(CalibrationOptionSpecs(), "", "--loss", "tukey"), "--loss: tukey not in {none,huber,cauchy}");
  ExpectInDocs(OptionsMarkdownTable(CalibrationOptionSpecs()));
}

TEST(TargetPrintOptionSpecs, OneRuleForTheFlagAndThePrint) {
  ExpectOneRuleEverywhere<TargetPrintOptions>(
      TargetPrintOptionSpecs(), [](const TargetPrintOptions& o) { return TargetPng(DefaultTarget(), o.dpi).status(); });
  ExpectInDocs(OptionsMarkdownTable(TargetPrintOptionSpecs()));
}

}  // namespace
}  // namespace hexcal::cli

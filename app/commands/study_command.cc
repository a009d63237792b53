// hexcal study --session DIR --select N [--subsets 6000] [--criterion O1] [--secondary C] [--starts 1]
//   [--seed 1] [--threads T] [--plots DIR] [--force] [--wait] [--json]
//
// The section 8 study on a recorded session (workflow/study_step.h,
// docs/calibration.md).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "workflow/study_step.h"

namespace hexcal::cli {
namespace {

struct StudyCliOptions {
  workflow::StudyRequest request;
  std::string criterion = "O1";
  std::string secondary;  // empty: none
  bool json = false, wait = false;
};

StatusOr<Criterion> CriterionOption(const std::string& flag, const std::string& text) {
  if (std::optional<Criterion> criterion = ParseCriterion(text)) return *criterion;
  std::string names;
  for (const auto& [name, criterion] : CriterionNames()) names += (names.empty() ? "" : ", ") + name;
  return Status::Error(flag + ": '" + text + "' is not a criterion (" + names + ")");
}

int RunStudy(const StudyCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::StudyRequest request = cli.request;
  request.wait = cli.wait ? LockWait::kForever : LockWait::kNo;
  StatusOr<Criterion> criterion = CriterionOption("--criterion", cli.criterion);
  if (!criterion.ok()) return ReportError(err, "study", criterion.status());
  request.study.criterion = *criterion;
  if (!cli.secondary.empty()) {
    StatusOr<Criterion> secondary = CriterionOption("--secondary", cli.secondary);
    if (!secondary.ok()) return ReportError(err, "study", secondary.status());
    request.study.secondary = *secondary;
  }
  TerminalJob job;
  StatusOr<workflow::StudyOutcome> outcome = workflow::RunStudy(request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "study", outcome.status());
  out << (cli.json ? workflow::ToJson(*outcome).dump(2) + "\n" : workflow::FormatStudySummary(*outcome));
  return kExitOk;
}

}  // namespace

void AddStudyCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<StudyCliOptions>();
  SubsetStudyOptions& study = options->request.study;
  CLI::App* sub = app.add_subcommand(
      "study", "the section 8 study: IOOPS's subset of a session's poses against random subsets (Figs. 18, 19)");
  sub->add_option("--session", options->request.session, "session folder with measured images and readings")
      ->required();
  sub->add_option("--select", study.select, "poses per subset (N; the paper's 13)")
      ->check(CountRange(kParamsPerLeg, 100000))
      ->required();
  sub->add_option("--subsets", study.subsets, "random subsets (K)")
      ->check(CountRange(1, 1000000))
      ->capture_default_str();
  sub->add_option("--criterion", options->criterion, "IOOPS's criterion (O1..O4, D, A, E, S; section 8 used O4)")
      ->capture_default_str();
  sub->add_option("--secondary", options->secondary, "section 6.2's secondary criterion (default: none)");
  sub->add_option("--starts", study.selection_starts, "IOOPS runs from random initial subsets; the best is kept")
      ->check(CountRange(1, 1000))
      ->capture_default_str();
  sub->add_flag("--weighted-selection,!--unweighted-selection", options->request.weighted_selection,
                "IOOPS weighs each row by its residual's standard deviation under the session's noise model "
                "(the default; --unweighted-selection: the paper's J_P)");
  sub->add_option("--seed", study.seed, "seed of the IOOPS starts and the random subsets")->capture_default_str();
  sub->add_option("--threads", study.num_threads, "subsets at once (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--plots", options->request.plots, "write Figs. 18 and 19 as SVG and PNG into this folder");
  sub->add_flag("--force", options->request.force, "overwrite the --plots figures if they exist");
  sub->add_flag("--wait", options->wait,
                "when another program writes the session, wait for it instead of stopping (exit 3)");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunStudy(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

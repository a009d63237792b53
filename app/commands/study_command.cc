// hexcal study --session DIR [--select 13] [--subsets 6000] [--criterion O1] [--secondary C] [--starts 1]
//   [--unweighted-selection] [--seed 1] [--threads T] [--plots DIR] [--force] [--wait] [--no-save] [--json]
//
// The section 8 study on a recorded session (workflow/study_step.h,
// docs/calibration.md), kept in DIR/study (session/session_study.h). The
// options are the table of workflow/study_options.h (docs/cli.md lists it).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "workflow/study_options.h"
#include "workflow/study_step.h"

namespace hexcal::cli {
namespace {

struct StudyCliOptions {
  workflow::StudyRequest request;
  std::shared_ptr<OptionEntries> study = std::make_shared<OptionEntries>();
  OptionFlagNames flags;
  bool json = false, wait = false, no_save = false;
};

int RunStudy(const StudyCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::StudyRequest request = cli.request;
  if (Status s = ApplyOptionEntries(workflow::StudyOptions(), *cli.study, &request, "study"); !s.ok())
    return ReportError(err, "study", s);
  request.wait = cli.wait ? LockWait::kForever : LockWait::kNo;
  request.save = !cli.no_save;
  TerminalJob job;
  StatusOr<workflow::StudyOutcome> outcome = workflow::RunStudy(request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "study", outcome.status(), cli.flags);
  out << (cli.json ? JsonText(workflow::ToJson(*outcome)) : workflow::FormatStudySummary(*outcome));
  return kExitOk;
}

}  // namespace

void AddStudyCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<StudyCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "study", "the section 8 study: IOOPS's subset of a session's poses against random subsets (Figs. 18, 19)");
  sub->add_option("--session", options->request.session, "session folder with measured images and readings")
      ->required();
  AddOptionFlags(sub, workflow::StudyOptions(), options->study, &options->flags);
  sub->add_option("--plots", options->request.plots, "also write Figs. 18 and 19 as SVG and PNG into this folder");
  sub->add_flag("--force", options->request.force, "overwrite the --plots figures if they exist");
  sub->add_flag("--wait", options->wait,
                "when another program writes the session, wait for it instead of stopping (exit 3)");
  sub->add_flag("--no-save", options->no_save,
                "print the study without keeping it in DIR/study (which the report and the GUI show)");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunStudy(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

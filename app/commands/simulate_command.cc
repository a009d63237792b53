// hexcal simulate --robot R [--sets random,boundary,plan.csv,...] [--poses N] [--runs 100] [--seed S]
//   [--perturb 0.5] [--random-box x:MIN:MAX,...] [--weighted] [--threads T] [--sweep A:B]
//   [--noise-position 0.001 --noise-angle 0.01 --noise-leg 0.001] [--json] [--csv FILE] [--plots DIR]
//
// The options and their defaults are the tables of workflow/simulate_options.h
// and core/noise_model.h (docs/cli.md lists them).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/noise_model.h"
#include "workflow/simulate_options.h"
#include "workflow/simulate_step.h"

namespace hexcal::cli {
namespace {

struct SimulateCliOptions {
  workflow::SimulateRequest request;
  bool json = false;
  std::shared_ptr<OptionEntries> simulate = std::make_shared<OptionEntries>();  // over request
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();     // --noise-* over study.noise
  OptionFlagNames flags;
};

int RunSimulate(const SimulateCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::SimulateRequest request = cli.request;
  if (Status s = ApplyOptionEntries(workflow::SimulateOptions(), *cli.simulate, &request, "simulate"); !s.ok())
    return ReportError(err, "simulate", s);
  request.poses_given = OptionGiven(*cli.simulate, "poses");
  request.noise_entries = *cli.noise;
  TerminalJob job;
  StatusOr<workflow::SimulateOutcome> outcome = workflow::RunSimulationStudy(request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "simulate", outcome.status(), cli.flags);
  out << (cli.json ? JsonText(workflow::ToJson(*outcome)) : workflow::FormatSimulateSummary(*outcome));
  return kExitOk;
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SimulateCliOptions>();
  CLI::App* sub = app.add_subcommand("simulate", "the section 7 study: parameter error of pose sets (Figs. 14, 15)");
  sub->add_option("--robot", options->request.robot, "nominal robot file or preset name")->required();
  AddOptionFlags(sub, workflow::SimulateOptions(), options->simulate, &options->flags);
  AddOptionFlags(sub, NoiseModelOptions(), options->noise, &options->flags, "noise-");
  sub->add_option("--csv", options->request.csv, "write the table(s) as CSV");
  sub->add_option("--plots", options->request.plots, "write Fig. 14 (and 15) as SVG and PNG into this folder");
  sub->add_flag("--force", options->request.force, "overwrite the --csv table and the --plots figures if they exist");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunSimulate(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

// hexcal simulate --robot R --sets random,boundary,plan.csv[,...] [--poses N] [--runs 100] [--seed S]
//   [--perturb 0.5] [--noise-position 0.001 --noise-angle 0.01 --noise-leg 0.001] [--threads T]
//   [--sweep A:B] [--json] [--csv FILE] [--plots DIR]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/noise_model.h"
#include "core/simulation.h"
#include "workflow/simulate_step.h"

namespace hexcal::cli {
namespace {

struct SimulateCliOptions {
  workflow::SimulateRequest request;
  bool json = false;
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-* over study.noise
};

int RunSimulate(const SimulateCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::SimulateRequest request = cli.request;
  request.noise_entries = *cli.noise;
  TerminalJob job;
  StatusOr<workflow::SimulateOutcome> outcome = workflow::RunSimulationStudy(request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "simulate", outcome.status());
  out << (cli.json ? JsonText(workflow::ToJson(*outcome)) : workflow::FormatSimulateSummary(*outcome));
  return kExitOk;
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SimulateCliOptions>();
  CLI::App* sub = app.add_subcommand("simulate", "the section 7 study: parameter error of pose sets (Figs. 14, 15)");
  sub->add_option("--robot", options->request.robot, "nominal robot file or preset name")->required();
  sub->add_option("--sets", options->request.sets, "comma-separated: random, boundary or pose CSV files")
      ->capture_default_str();
  CLI::Option* poses = sub->add_option("--poses", options->request.poses, "poses of the random set (and of boundary if given)")
                           ->check(CountRange(1, 100000))
                           ->capture_default_str();
  const OptionSpec<SimulationOptions>& runs = *FindOption(SimulationOptionSpecs(), "runs");
  sub->add_option(runs.Flag(), options->request.study.runs, runs.help)
      ->check(CountRange(static_cast<long long>(runs.min), static_cast<long long>(runs.max)))
      ->capture_default_str();
  sub->add_option("--seed", options->request.study.seed, "random seed")->capture_default_str();
  sub->add_option("--perturb", options->request.study.perturb, "half-width of the parameter perturbation (robot unit)")
      ->capture_default_str();
  AddOptionFlags(sub, NoiseModelOptions(), options->noise, "noise-");
  sub->add_option("--random-box", options->request.random_box,
                  "draw random sets in this box, e.g. x:-5:5,y:-5:5,z:50:57,q1:-20:20,q2:-20:20,q3:-20:20 "
                  "(intersected with the robot's pose box; the robot's constraints still apply)");
  sub->add_flag("--weighted", options->request.weighted,
                "calibrate with each residual divided by its standard deviation under the noise model");
  sub->add_option("--threads", options->request.study.num_threads, "runs at once (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--sweep", options->request.sweep, "also the error against the number of poses, MIN:MAX (Fig. 15)");
  sub->add_option("--csv", options->request.csv, "write the table(s) as CSV");
  sub->add_option("--plots", options->request.plots, "write Fig. 14 (and 15) as SVG and PNG into this folder");
  sub->add_flag("--force", options->request.force, "overwrite the --csv table and the --plots figures if they exist");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] {
    options->request.poses_given = poses->count() > 0;
    *exit_code = RunSimulate(*options, std::cout, std::cerr);
  });
}

}  // namespace hexcal::cli

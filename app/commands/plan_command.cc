// hexcal plan (--robot R | --session DIR) --out plan.csv [--candidates FILE] [--settings plan.yaml]
//   [every option of workflow::PlanSetupOptions(): --poses, --criterion, --secondary, --tabu, ...]
//   [--noise-position p --noise-angle a --noise-leg l] [--history history.csv] [--json]
//
// The options and their defaults are the tables of workflow/plan_options.h
// and core/noise_model.h (docs/cli.md lists them).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/noise_model.h"
#include "workflow/plan_step.h"

namespace hexcal::cli {
namespace {

struct PlanCliOptions {
  workflow::PlanRequest request;
  std::shared_ptr<OptionEntries> planner = std::make_shared<OptionEntries>();
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();
  OptionFlagNames flags;
  bool force = false, json = false;
};

int RunPlanCommand(PlanCliOptions cli, std::ostream& out, std::ostream& err) {
  cli.request.planner_entries = *cli.planner;
  cli.request.noise_entries = *cli.noise;
  for (const std::string& path : {cli.request.out, cli.request.history}) {
    if (Status s = CheckOutputFree(path, cli.force); !s.ok()) return ReportError(err, "plan", s);
  }
  TerminalJob job;
  StatusOr<workflow::PlanOutcome> outcome = workflow::PlanFromRequest(cli.request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "plan", outcome.status(), cli.flags);
  if (cli.json) {
    out << JsonText(workflow::ToJson(*outcome));
  } else {
    out << workflow::FormatPlanSummary(*outcome);
  }
  return kExitOk;
}

}  // namespace

void AddPlanCommand(CLI::App& app, int* exit_code) {
  auto o = std::make_shared<PlanCliOptions>();
  CLI::App* sub = app.add_subcommand("plan", "choose N measurement poses (IOOPS, paper section 4)");
  auto* robot = sub->add_option("--robot", o->request.robot, "robot file or preset name");
  auto* session = sub->add_option("--session", o->request.session,
                                  "session folder: its robot, noise model and (points sessions) the tracker's "
                                  "per-pose noise and line of sight; docs/planner.md");
  robot->excludes(session);
  session->excludes(robot);
  sub->add_option("--candidates", o->request.candidates_file, "candidate pose CSV (x,y,z,q1,q2,q3)");
  AddOptionFlags(sub, workflow::PlanSetupOptions(), o->planner, &o->flags);
  AddOptionFlags(sub, NoiseModelOptions(), o->noise, &o->flags, "noise-");
  sub->add_option("--settings", o->request.settings,
                  "plan settings YAML (noise, planner, camera visibility); flags override it; docs/planner.md");
  sub->add_option("--out", o->request.out, "plan CSV: x,y,z,q1,q2,q3,L1..L6")->required();
  sub->add_option("--history", o->request.history, "indices per iteration CSV (figs 6, 10-12)");
  sub->add_flag("--force", o->force, "overwrite --out and --history if they exist");
  sub->add_flag("--json", o->json, "print one JSON object on stdout");
  sub->get_option("--candidate-kind")->excludes(sub->get_option("--candidates"));
  sub->callback([=] { *exit_code = RunPlanCommand(*o, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

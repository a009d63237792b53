// hexcal acquire --session DIR --controller URL --camera URL [--poses FILE] [--settle SECONDS]
//                [--grab-timeout MS] [--holdout-every N] [--seed N] [--wait] [--json]
//
// Moves the robot to each planned pose and records an image and the leg
// readings there (workflow/acquire_step.h, docs/acquisition.md). The options
// --settle, --grab-timeout and --holdout-every are the table of
// workflow/acquire_options.h (docs/cli.md lists it). Ctrl-C stops
// before the current pose's frame (a machine's move at once) or after its
// record (exit 1, cancelled); running the command again goes on from there.
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "workflow/acquire_step.h"

namespace hexcal::cli {
namespace {

struct AcquireCliOptions {
  workflow::AcquireRequest request;
  std::shared_ptr<OptionEntries> options = std::make_shared<OptionEntries>();  // over request.options
  OptionFlagNames flags;
  bool wait = false, json = false;
};

std::atomic<bool> interrupted{false};

// The first Ctrl-C asks the run to stop between poses; a second one kills as
// usual (the run resumes after a kill too).
void StopAfterThisPose(int) {
  interrupted = true;
  std::signal(SIGINT, SIG_DFL);
}

int RunAcquireCommand(AcquireCliOptions cli, std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(workflow::AcquireOptionSpecs(), *cli.options, &cli.request.options, "acquire");
      !s.ok())
    return ReportError(err, "acquire", s);
  cli.request.options.wait = cli.wait ? LockWait::kForever : LockWait::kNo;
  TerminalJob job("", &err);  // a line per pose on stderr; stdout stays one JSON object with --json
  JobHooks hooks = job.hooks();
  hooks.cancel = &interrupted;
  std::signal(SIGINT, StopAfterThisPose);
  StatusOr<workflow::AcquireResult> result = workflow::AcquirePlan(cli.request, hooks);
  std::signal(SIGINT, SIG_DFL);
  if (!result.ok()) return ReportError(err, "acquire", result.status(), cli.flags);
  if (cli.json) {
    out << JsonText(workflow::ToJson(*result));
  } else {
    out << workflow::FormatAcquireSummary(*result);
  }
  // Failed poses are listed above; the exit code tells scripts the plan is not complete.
  return result->Count(workflow::PoseState::kFailed) > 0 ? kExitFailure : kExitOk;
}

}  // namespace

void AddAcquireCommand(CLI::App& app, int* exit_code) {
  auto cli = std::make_shared<AcquireCliOptions>();
  workflow::AcquireRequest& request = cli->request;
  CLI::App* sub = app.add_subcommand("acquire", "move to each planned pose and record an image and the leg readings");
  sub->add_option("--session", request.session, "session folder to record into")->required();
  sub->add_option("--controller", request.controller, std::string("robot controller: ") + workflow::kControllerForms)
      ->required();
  sub->add_option("--camera", request.camera, std::string("camera: ") + workflow::kFrameSourceForms)->required();
  sub->add_option("--poses", request.poses, "pose CSV (x,y,z,q1,q2,q3); default: the session's plan.csv");
  AddOptionFlags(sub, workflow::AcquireOptionSpecs(), cli->options, &cli->flags);
  sub->add_option("--seed", request.seed, "seed of the sim world's hidden truth and noise (sim only)")
      ->capture_default_str();
  sub->add_flag("--wait", cli->wait,
                "when another program writes the session, wait for it instead of stopping (exit 3)");
  sub->add_flag("--json", cli->json, "print one JSON object on stdout (progress on stderr)");
  sub->callback([=] { *exit_code = RunAcquireCommand(*cli, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

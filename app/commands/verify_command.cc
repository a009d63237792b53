// hexcal verify --session DIR --controller URL --camera URL [--poses FILE] [--settle SECONDS]
//               [--keep-images DIR [--force]] [--seed N] [--json]
//
// Drives the controller to each pose and checks through the camera where the
// platform really is, in the session's registered frames
// (workflow/verify_step.h, docs/acquisition.md): the controller's pose error
// before a calibration is loaded into it, and after. Ctrl-C stops between
// poses.
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "devices/controller.h"
#include "devices/frame_source.h"
#include "workflow/acquire_options.h"
#include "workflow/verify_step.h"

namespace hexcal::cli {
namespace {

struct VerifyCliOptions {
  workflow::VerifyRequest request;
  bool json = false;
};

std::atomic<bool> verify_interrupted{false};
void StopVerifying(int) {
  verify_interrupted = true;
  std::signal(SIGINT, SIG_DFL);
}

int RunVerifyCommand(const VerifyCliOptions& cli, std::ostream& out, std::ostream& err) {
  TerminalJob job("", &err);
  JobHooks hooks = job.hooks();
  hooks.cancel = &verify_interrupted;
  std::signal(SIGINT, StopVerifying);
  StatusOr<workflow::VerifyResult> result = workflow::VerifyPoses(cli.request, hooks);
  std::signal(SIGINT, SIG_DFL);
  if (!result.ok()) return ReportError(err, "verify", result.status());
  if (cli.json) {
    out << JsonText(workflow::ToJson(*result));
  } else {
    out << workflow::FormatVerifySummary(*result);
  }
  return result->Seen() < static_cast<int>(result->poses.size()) ? kExitFailure : kExitOk;
}

}  // namespace

void AddVerifyCommand(CLI::App& app, int* exit_code) {
  auto cli = std::make_shared<VerifyCliOptions>();
  workflow::VerifyRequest& request = cli->request;
  CLI::App* sub =
      app.add_subcommand("verify", "move to poses and check through the camera where the platform really is");
  sub->add_option("--session", request.session, "a calibrated session: its camera, target and registered frames")
      ->required();
  sub->add_option("--controller", request.controller, std::string("robot controller: ") + workflow::kControllerForms)
      ->required();
  sub->add_option("--camera", request.camera, std::string("camera: ") + workflow::kFrameSourceForms)->required();
  sub->add_option("--poses", request.poses, "pose CSV (x,y,z,q1,q2,q3); default: the session's plan.csv");
  // The range of the Acquire step's settle time (workflow/acquire_options.h).
  const OptionSpec<workflow::AcquireOptions>& settle = *FindOption(workflow::AcquireOptionSpecs(), "settle");
  sub->add_option("--settle", request.settle_seconds, "seconds to wait after each move, before the frame")
      ->check(CLI::Range(settle.min, settle.max))
      ->capture_default_str();
  sub->add_option("--keep-images", request.images_out,
                  "a folder to keep each frame in (check_000k.png; not the session's images/)");
  sub->add_flag("--force", request.force, "replace check_000k.png files in the --keep-images folder");
  sub->add_option("--seed", request.seed, "seed of the sim world's hidden truth (sim only)")->capture_default_str();
  sub->add_flag("--json", cli->json, "print one JSON object on stdout (progress on stderr)");
  sub->callback([=] { *exit_code = RunVerifyCommand(*cli, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

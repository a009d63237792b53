// hexcal demo [--robot inria-left-hand|deltalab-table|FILE] [--out DIR] [--poses 24] [--holdout 8]
//             [--random-poses] [--from-pixels | --two-stage] [--focal-error PERCENT]
//             [--instrument camera|points] [--point-sigma MM] [--seed 1] [--force] [--json]
//
// The whole calibration flow on a virtual robot and camera (workflow/demo.h,
// docs/session.md). The options with a range are the table of
// workflow/demo_options.h (docs/cli.md lists it).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "workflow/demo.h"
#include "workflow/demo_options.h"

namespace hexcal::cli {
namespace {

struct DemoCliOptions {
  workflow::DemoRequest request;
  std::shared_ptr<OptionEntries> demo = std::make_shared<OptionEntries>();  // over request
  OptionFlagNames flags;
  bool json = false;
};

int RunDemoCommand(const DemoCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::DemoRequest request = cli.request;
  if (Status s = ApplyOptionEntries(workflow::DemoOptions(), *cli.demo, &request, "demo"); !s.ok())
    return ReportError(err, "demo", s);
  TerminalJob job("", cli.json ? &err : &out);  // the step log; stdout stays one JSON object with --json
  StatusOr<workflow::DemoResult> result = workflow::RunDemo(request, job.hooks());
  if (!result.ok()) return ReportError(err, "demo", result.status(), cli.flags);
  if (cli.json) {
    out << JsonText(workflow::ToJson(*result));
  } else {
    out << workflow::FormatDemoSummary(*result);
  }
  return kExitOk;
}

}  // namespace

void AddDemoCommand(CLI::App& app, int* exit_code) {
  auto cli = std::make_shared<DemoCliOptions>();
  workflow::DemoRequest& request = cli->request;
  CLI::App* sub = app.add_subcommand("demo", "the whole calibration flow on a virtual robot and camera");
  sub->add_option("--robot", request.robot, "robot file or preset name (inria-left-hand, deltalab-table)")
      ->capture_default_str();
  sub->add_option("--out", request.out, "session folder to write")->capture_default_str();
  AddOptionFlags(sub, workflow::DemoOptions(), cli->demo, &cli->flags);
  sub->add_flag("--from-pixels,!--two-stage", request.from_pixels,
                "calibrate from the tag corners, estimating the focal length (the default; with --instrument points: "
                "from the points, estimating the reflectors), or --two-stage: fit the legs to the measured poses only");
  sub->add_flag("--force", request.force, "replace an earlier demo in --out");
  sub->add_flag("--json", cli->json, "print one JSON object on stdout (progress on stderr)");
  sub->callback([=] { *exit_code = RunDemoCommand(*cli, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

// hexcal demo [--robot inria-left-hand|deltalab-table|FILE] [--out DIR] [--poses 24] [--holdout 8]
//             [--random-poses] [--from-pixels | --two-stage] [--focal-error PERCENT]
//             [--instrument camera|points] [--point-sigma MM] [--seed 1] [--force] [--json]
//
// The whole calibration flow on a virtual robot and camera (workflow/demo.h,
// docs/session.md).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "workflow/demo.h"

namespace hexcal::cli {
namespace {

int RunDemoCommand(const workflow::DemoRequest& request, bool json, std::ostream& out, std::ostream& err) {
  TerminalJob job("", json ? &err : &out);  // the step log; stdout stays one JSON object with --json
  StatusOr<workflow::DemoResult> result = workflow::RunDemo(request, job.hooks());
  if (!result.ok()) return ReportError(err, "demo", result.status());
  if (json) {
    out << JsonText(workflow::ToJson(*result));
  } else {
    out << workflow::FormatDemoSummary(*result);
  }
  return kExitOk;
}

}  // namespace

void AddDemoCommand(CLI::App& app, int* exit_code) {
  auto request = std::make_shared<workflow::DemoRequest>();
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("demo", "the whole calibration flow on a virtual robot and camera");
  sub->add_option("--robot", request->robot, "robot file or preset name (inria-left-hand, deltalab-table)")
      ->capture_default_str();
  sub->add_option("--out", request->out, "session folder to write")->capture_default_str();
  sub->add_option("--poses", request->poses, "planned calibration poses")
      ->check(CountRange(workflow::kMinDemoPoses, workflow::kMaxDemoPoses, "each pose is a rendered image"))
      ->capture_default_str();
  sub->add_option("--holdout", request->holdout, "random poses kept out to validate (0: none)")
      ->check(CountRange(0, workflow::kMaxDemoHoldout, "each pose is a rendered image"))
      ->capture_default_str();
  sub->add_flag("--random-poses", request->random_poses,
                "record --poses random feasible poses the camera sees instead of an IOOPS plan (for hexcal study)");
  sub->add_flag("--from-pixels,!--two-stage", request->from_pixels,
                "calibrate from the tag corners, estimating the focal length (the default; with --instrument points: "
                "from the points, estimating the reflectors), or --two-stage: fit the legs to the measured poses only");
  sub->add_option("--focal-error", request->focal_error_percent,
                  "give the calibration a camera file whose focal length is off by this many percent (-20..20); "
                  "the images keep the true one")
      ->capture_default_str();
  auto instrument = std::make_shared<std::string>("camera");
  auto point_sigma_mm = std::make_shared<double>(request->point_sigma_m * 1000);
  sub->add_option("--instrument", *instrument,
                  "what measures the poses: camera (rendered images of the board) or points (a laser tracker's "
                  "4 reflectors)")
      ->check(CLI::IsMember({"camera", "points"}))
      ->capture_default_str();
  sub->add_option("--point-sigma", *point_sigma_mm,
                  "with --instrument points: the tracker's sigma on each coordinate, mm (0.0001 to 1)")
      ->capture_default_str();
  sub->add_option("--seed", request->seed, "seed of the truth, the candidates and the noise")->capture_default_str();
  sub->add_flag("--force", request->force, "replace an earlier demo in --out");
  sub->add_flag("--json", *json, "print one JSON object on stdout (progress on stderr)");
  sub->callback([=] {
    request->instrument = *instrument == "points" ? Instrument::kPoints : Instrument::kCamera;
    request->point_sigma_m = *point_sigma_mm / 1000;
    *exit_code = RunDemoCommand(*request, *json, std::cout, std::cerr);
  });
}

}  // namespace hexcal::cli

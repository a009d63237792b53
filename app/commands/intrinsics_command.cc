// hexcal intrinsics --target T --images DIR --out camera.yaml [--coverage coverage.png] [--min-views N]
//                   [--model radtan|rational|pinhole-equi] [--force] [--json]
#include <iostream>
#include <memory>
#include <optional>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "workflow/intrinsics_step.h"

namespace hexcal::cli {
namespace {

struct IntrinsicsCliOptions {
  workflow::IntrinsicsRequest request;
  std::string model = CameraModelName(CameraModel::kRadTan);
  bool json = false;
};

int RunIntrinsics(IntrinsicsCliOptions cli, std::ostream& out, std::ostream& err) {
  const std::optional<CameraModel> model = CameraModelFromName(cli.model);
  if (!model) return ReportError(err, "intrinsics", Status::BadInput("--model: unknown model '" + cli.model + "'"));
  cli.request.options.model = *model;
  TerminalJob job("intrinsics");
  StatusOr<workflow::IntrinsicsOutcome> outcome = workflow::CalibrateCameraFromFolder(cli.request, job.hooks());
  if (!outcome.ok()) return ReportError(err, "intrinsics", outcome.status());
  out << (cli.json ? JsonText(workflow::ToJson(*outcome)) : workflow::FormatIntrinsicsSummary(*outcome));
  return kExitOk;
}

}  // namespace

void AddIntrinsicsCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<IntrinsicsCliOptions>();
  CLI::App* sub = app.add_subcommand("intrinsics", "calibrate a camera from images of the target");
  sub->add_option("--target", options->request.target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  sub->add_option("--images", options->request.images, "folder of PNG/JPEG/TIFF images")->required();
  sub->add_option("--out", options->request.out, "camera file to write (OpenCV YAML)")->required();
  sub->add_option("--coverage", options->request.coverage, "corner coverage picture (default: OUT with .coverage.png)");
  sub->add_option("--min-views", options->request.options.min_views, "fewer usable images is an error")
      ->check(CountRange(1, 100000))
      ->capture_default_str();
  sub->add_option("--min-tags", options->request.options.min_tags_per_view, "target tags for an image to be used")
      ->capture_default_str();
  sub->add_option("--model", options->model,
                  "distortion model: radtan (k1 k2 p1 p2 k3), rational (k1..k6 p1 p2) or pinhole-equi (fisheye k1..k4)")
      ->check(CLI::IsMember({"radtan", "rational", "pinhole-equi"}))
      ->capture_default_str();
  sub->add_option("--threads", options->request.options.threads, "images detected in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--max-rms", options->request.options.max_rms_px,
                  "a larger reprojection RMS (px) is an error: the target or the model is wrong")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_flag("--keep-outliers", options->request.options.keep_outliers,
                "keep views that fit far worse than the median view (they are still named)");
  sub->add_flag("--force", options->request.force, "overwrite an existing camera file");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunIntrinsics(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

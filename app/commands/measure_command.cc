// hexcal measure --camera C --target T --images DIR --out camera_poses.csv [--force] [--json]
// hexcal measure --points FILE [--reflectors FILE] --point-sigma S --out tracker_poses.csv [--force] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "workflow/measure_step.h"
#include "workflow/point_session.h"

namespace hexcal::cli {
namespace {

struct MeasureCliOptions {
  workflow::MeasureRequest request;
  std::string points, reflectors;  // --points: a tracker's points instead of images
  double point_sigma = 0;
  bool json = false;
};

// --points: each pose of a points file fitted to the reflectors (workflow/point_session.h).
int RunMeasurePoints(const MeasureCliOptions& cli, std::ostream& out, std::ostream& err) {
  if (!cli.request.camera.empty() || !cli.request.images.empty())
    return ReportError(err, "measure", Status::BadInput("--points measures a points file: no --camera or --images"));
  if (!(cli.point_sigma > 0))
    return ReportError(err, "measure",
                       Status::BadInput("--points needs --point-sigma (the points' sigma per coordinate, "
                                        "their unit) for points the file gives none"));
  StatusOr<workflow::PointMeasureResult> result = workflow::MeasurePointFile(
      {cli.points, cli.reflectors, cli.point_sigma}, cli.request.out, cli.request.force);
  if (!result.ok()) return ReportError(err, "measure", result.status());
  if (cli.json) {
    out << JsonText({{"out", cli.request.out}, {"poses", result->poses}, {"fitted", result->fitted},
                     {"reflectors_estimated", result->reflectors_estimated}});
  } else {
    out << "measured " << result->fitted << " of " << result->poses << " poses from their points"
        << (result->reflectors_estimated ? " (reflectors estimated from the poses)" : "") << "; wrote "
        << cli.request.out << "\n";
  }
  if (result->fitted == 0) return ReportError(err, "measure", Status::Failed("no pose could be fitted to its points"));
  return kExitOk;
}

// No image gave a pose. Bad input (exit 2, as calibrate --session has it)
// when no image that was searched shows the target: the wrong images, or a
// target file that does not describe the printed board. A failed computation
// (exit 1) when images show it but fit it badly, or none could be read.
Status NoPose(const workflow::MeasureResult& result, const std::string& diagnosis) {
  auto count = [&](const char* status) {
    const auto it = result.counts.find(status);
    return it == result.counts.end() ? 0 : it->second;
  };
  const int hidden = count("no_target") + count("too_few_tags");
  const int shown = count("high_rms") + count("ambiguous") + count("failed");
  if (hidden > 0 && shown == 0) {
    std::string statuses;
    for (const auto& [status, n] : result.counts)
      statuses += (statuses.empty() ? "" : ", ") + status + " " + std::to_string(n);
    return Status::BadInput("no image shows the target (" + statuses + " of " + std::to_string(result.rows.size()) +
                            " images); check that these are images of the board and that --target describes it as "
                            "printed (hexcal detect --images IMAGE says what an image holds)");
  }
  return Status::Failed("no image gave a pose" + (diagnosis.empty() ? "" : ": " + diagnosis));
}

int RunMeasure(const MeasureCliOptions& cli, std::ostream& out, std::ostream& err) {
  if (!cli.points.empty()) return RunMeasurePoints(cli, out, err);
  if (cli.request.camera.empty() || cli.request.images.empty())
    return ReportError(err, "measure",
                       Status::BadInput("give --camera and --images (or --points for a tracker's points)"));
  TerminalJob job("measure");
  StatusOr<workflow::MeasureResult> result = workflow::MeasureFolder(cli.request, job.hooks());
  if (!result.ok()) return ReportError(err, "measure", result.status());
  out << (cli.json ? JsonText(workflow::ToJson(*result)) : workflow::FormatMeasureSummary(*result));
  const std::string diagnosis = workflow::DiagnoseMeasurements(*result);
  if (result->ok() == 0) return ReportError(err, "measure", NoPose(*result, diagnosis));
  if (!diagnosis.empty()) err << "hexcal measure: warning: " << diagnosis << "\n";
  return kExitOk;
}

}  // namespace

void AddMeasureCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<MeasureCliOptions>();
  CLI::App* sub = app.add_subcommand("measure", "camera_from_target of every image in a folder");
  sub->add_option("--camera", options->request.camera, "camera file (OpenCV or ROS YAML)");
  sub->add_option("--target", options->request.target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  sub->add_option("--images", options->request.images, "an image, or a folder of PNG/JPEG/TIFF images");
  sub->add_option("--points", options->points,
                  "instead of images: a points file (CSV pose,point,x,y,z[,sigma] or SpatialAnalyzer ASCII); writes "
                  "each pose fitted to the reflectors (tracker_from_reflectors)");
  sub->add_option("--reflectors", options->reflectors,
                  "with --points: the reflectors' positions, CSV point,x,y,z (default: estimated from the poses)");
  sub->add_option("--point-sigma", options->point_sigma,
                  "with --points: sigma of each coordinate where the file gives none, the points' unit");
  sub->add_option("--out", options->request.out, "camera poses CSV to write (camera_from_target per image, not robot measurements)")->required();
  sub->add_option("--threads", options->request.options.threads, "images measured in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--min-tags", options->request.options.pose.min_tags, "fewer target tags: too_few_tags")
      ->capture_default_str();
  sub->add_option("--max-rms", options->request.options.pose.max_rms_px, "larger reprojection RMS (px): high_rms")
      ->capture_default_str();
  sub->add_option("--min-margin", options->request.options.detector.min_decision_margin,
                  "reject tag decodes with a smaller decision margin (grey levels)")
      ->capture_default_str();
  sub->add_option("--max-hamming", options->request.options.detector.max_hamming,
                  "accept tag decodes with at most this many corrected bits (0-2)")
      ->capture_default_str();
  sub->add_flag("--force", options->request.force, "overwrite an existing output");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunMeasure(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

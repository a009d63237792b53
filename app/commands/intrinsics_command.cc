// hexcal intrinsics --target T --images DIR --out camera.yaml [--coverage coverage.png] [--min-views N]
//                   [--force] [--json]
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "vision/intrinsics.h"
#include "vision/measure.h"

namespace hexcal::cli {
namespace {

struct IntrinsicsCliOptions {
  std::string target = kDefaultTargetName, images, out, coverage;
  IntrinsicsOptions calibration;
  bool force = false, json = false;
};

// "camera.yaml" -> "camera.coverage.png"
std::string DefaultCoveragePath(const std::string& out) {
  std::filesystem::path path(out);
  path.replace_extension(".coverage.png");
  return path.string();
}

int RunIntrinsics(const IntrinsicsCliOptions& cli, std::ostream& out, std::ostream& err) {
  StatusOr<Target> target = LoadTarget(cli.target);
  if (!target.ok()) return ReportError(err, "intrinsics", target.status());
  StatusOr<std::vector<std::string>> files = ListImages(cli.images);
  if (!files.ok()) return ReportError(err, "intrinsics", files.status());
  std::error_code fs_error;
  if (Status s = CheckOutputFree(cli.out, cli.force); !s.ok()) return ReportError(err, "intrinsics", s);
  ProgressBar progress("intrinsics");
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsics(*files, *target, cli.calibration,
                                                          {[&](int done, int total) { progress.Update(done, total); }});
  // Unusable images (sizes, too few views) are the usual cause: bad input.
  if (!result.ok()) return ReportError(err, "intrinsics", result.status());
  if (Status s = SaveCamera(result->camera, cli.out, ExtrasOf(*result)); !s.ok()) {
    return ReportError(err, "intrinsics", s.AsFailure());
  }
  const std::string coverage_path = cli.coverage.empty() ? DefaultCoveragePath(cli.out) : cli.coverage;
  std::vector<uint8_t> png;
  cv::imencode(".png", CoverageImage(*result), png);
  if (Status s = WriteFileAtomically(coverage_path, std::string(png.begin(), png.end())); !s.ok()) {
    return ReportError(err, "intrinsics", s.AsFailure());
  }
  const Camera& c = result->camera;
  const std::array<double, 9> values = {
      c.fx, c.fy, c.cx, c.cy, c.distortion[0], c.distortion[1], c.distortion[2], c.distortion[3], c.distortion[4]};
  static const char* kNames[9] = {"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3"};
  if (cli.json) {
    nlohmann::json parameters, views = nlohmann::json::array();
    for (int i = 0; i < 9; ++i) parameters[kNames[i]] = {{"value", values[i]}, {"std_dev", result->std_dev[i]}};
    for (const CalibrationView& view : result->views) {
      views.push_back({{"file", view.file},
                       {"used", view.used},
                       {"tags", view.tags},
                       {"rms_px", view.rms_px},
                       {"reason", view.reason}});
    }
    out << nlohmann::json{{"out", cli.out},
                          {"coverage", coverage_path},
                          {"coverage_fraction", CoverageFraction(*result)},
                          {"image_width", c.width},
                          {"image_height", c.height},
                          {"rms_px", result->rms_px},
                          {"used_views", result->used_views},
                          {"parameters", parameters},
                          {"views", views}}
               .dump(2)
        << "\n";
    return kExitOk;
  }
  out << "camera " << c.width << " x " << c.height << " from " << result->used_views << " of " << files->size()
      << " images, RMS " << result->rms_px << " px\n";
  for (int i = 0; i < 9; ++i) out << "  " << kNames[i] << " = " << values[i] << " +- " << result->std_dev[i] << "\n";
  for (const CalibrationView& view : result->views) {
    if (!view.used) out << "  not used: " << view.file << ": " << view.reason << "\n";
  }
  out << "written to " << cli.out << "; corner coverage " << 100 * CoverageFraction(*result) << " % in "
      << coverage_path << "\n";
  return kExitOk;
}

}  // namespace

void AddIntrinsicsCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<IntrinsicsCliOptions>();
  CLI::App* sub = app.add_subcommand("intrinsics", "calibrate a camera from images of the target");
  sub->add_option("--target", options->target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  sub->add_option("--images", options->images, "folder of PNG/JPEG/TIFF images")->required();
  sub->add_option("--out", options->out, "camera file to write (OpenCV YAML)")->required();
  sub->add_option("--coverage", options->coverage, "corner coverage picture (default: OUT with .coverage.png)");
  sub->add_option("--min-views", options->calibration.min_views, "fewer usable images is an error")
      ->check(CountRange(1, 100000))
      ->capture_default_str();
  sub->add_option("--min-tags", options->calibration.min_tags_per_view, "target tags for an image to be used")
      ->capture_default_str();
  sub->add_option("--threads", options->calibration.threads, "images detected in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_flag("--force", options->force, "overwrite an existing camera file");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunIntrinsics(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

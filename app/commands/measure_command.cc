// hexcal measure --camera C --target T --images DIR --out measurements.csv [--force] [--json]
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "vision/measure.h"

namespace hexcal::cli {
namespace {

struct MeasureCliOptions {
  std::string camera, target = kDefaultTargetName, images, out;
  MeasureOptions measure;
  bool force = false, json = false;
};

nlohmann::json MeasurementJson(const ImageMeasurement& m) {
  nlohmann::json j = {{"file", m.file},
                      {"status", PoseStatusName(m.pose.status)},
                      {"message", m.pose.message},
                      {"tags", m.pose.num_tags}};
  if (m.pose.has_pose) {
    const Vector6d v = VectorFromPose(m.pose.camera_from_target, EulerConvention::kXYZ);
    static const char* kNames[6] = {"x", "y", "z", "q1", "q2", "q3"};
    for (int k = 0; k < 6; ++k) {
      j["pose"][kNames[k]] = v[k];
      j["sigma"][kNames[k]] = std::sqrt(std::max(0.0, m.pose.covariance_vector(k, k)));
    }
    j["rms_px"] = m.pose.rms_px;
  }
  return j;
}

int RunMeasure(const MeasureCliOptions& cli, std::ostream& out, std::ostream& err) {
  StatusOr<Camera> camera = LoadCamera(cli.camera);
  if (!camera.ok()) return ReportError(err, "measure", camera.status());
  StatusOr<Target> target = LoadTarget(cli.target);
  if (!target.ok()) return ReportError(err, "measure", target.status());
  std::string error;
  if (!cli.measure.IsValid(&error)) return ReportError(err, "measure", Status::Error(error));
  StatusOr<std::vector<std::string>> files = ListImages(cli.images);
  if (!files.ok()) return ReportError(err, "measure", files.status());
  std::error_code fs_error;
  if (Status s = CheckOutputFree(cli.out, cli.force); !s.ok()) return ReportError(err, "measure", s);
  ProgressBar progress("measure");
  StatusOr<std::vector<ImageMeasurement>> measurements = MeasureImages(
      *files, *camera, *target, cli.measure, {[&](int done, int total) { progress.Update(done, total); }});
  if (!measurements.ok()) return ReportError(err, "measure", (measurements.status()).AsFailure());
  // Names relative to the folder, so that the table moves with the images.
  const bool folder = std::filesystem::is_directory(cli.images, fs_error);
  for (ImageMeasurement& m : *measurements) {
    if (folder) m.file = std::filesystem::path(m.file).filename().string();
  }
  if (Status s = WriteImageMeasurementsCsv(cli.out, *measurements); !s.ok()) {
    return ReportError(err, "measure", s.AsFailure());
  }
  std::map<std::string, int> counts;
  for (const ImageMeasurement& m : *measurements) ++counts[PoseStatusName(m.pose.status)];
  const int ok = counts["ok"];
  if (cli.json) {
    nlohmann::json results = nlohmann::json::array();
    for (const ImageMeasurement& m : *measurements) results.push_back(MeasurementJson(m));
    out << nlohmann::json{{"out", cli.out},
                          {"images", measurements->size()},
                          {"counts", counts},
                          {"length_unit", LengthUnitName(target->length_unit)},
                          {"results", results}}
               .dump(2)
        << "\n";
  } else {
    out << measurements->size() << " images:";
    for (const auto& [status, count] : counts) {
      if (count) out << " " << count << " " << status;
    }
    out << "; written to " << cli.out << " (camera_from_target, " << LengthUnitName(target->length_unit)
        << " and degrees)\n";
    for (const ImageMeasurement& m : *measurements) {
      if (m.pose.status != PoseStatus::kOk)
        out << "  " << m.file << ": " << PoseStatusName(m.pose.status) << ": " << m.pose.message << "\n";
    }
  }
  if (ok == 0) {
    err << "hexcal measure: no image gave a pose\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void AddMeasureCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<MeasureCliOptions>();
  CLI::App* sub = app.add_subcommand("measure", "camera_from_target of every image in a folder");
  sub->add_option("--camera", options->camera, "camera file (OpenCV or ROS YAML)")->required();
  sub->add_option("--target", options->target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  sub->add_option("--images", options->images, "an image, or a folder of PNG/JPEG/TIFF images")->required();
  sub->add_option("--out", options->out, "measurements CSV to write")->required();
  sub->add_option("--threads", options->measure.threads, "images measured in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_option("--min-tags", options->measure.pose.min_tags, "fewer target tags: too_few_tags")
      ->capture_default_str();
  sub->add_option("--max-rms", options->measure.pose.max_rms_px, "larger reprojection RMS (px): high_rms")
      ->capture_default_str();
  sub->add_option("--min-margin", options->measure.detector.min_decision_margin,
                  "reject tag decodes with a smaller decision margin (grey levels)")
      ->capture_default_str();
  sub->add_option("--max-hamming", options->measure.detector.max_hamming,
                  "accept tag decodes with at most this many corrected bits (0-2)")
      ->capture_default_str();
  sub->add_flag("--force", options->force, "overwrite an existing output");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunMeasure(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

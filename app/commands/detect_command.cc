// hexcal detect --images DIR|FILE [--target T | --family tag36h11 --border-bits 1] [--camera C]
//               [--threads 2] [--no-refine] [--json]
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/parallel.h"
#include "vision/detection.h"
#include "vision/layout_hint.h"
#include "vision/measure.h"

namespace hexcal::cli {
namespace {

struct DetectCliOptions {
  std::string images, camera, target;
  DetectorOptions detector;
  int threads = 2;  // images detected at once; 0 = every core
  bool no_refine = false;
  bool json = false;
};

nlohmann::json DetectionJson(const std::string& family, const TagDetection& tag) {
  nlohmann::json corners = nlohmann::json::array();
  for (const Eigen::Vector2d& c : tag.corners) corners.push_back({c.x(), c.y()});
  nlohmann::json json = {{"family", family},       {"id", tag.id},
                         {"corners", corners},     {"decision_margin", tag.decision_margin},
                         {"hamming", tag.hamming}, {"refined", tag.refined}};
  if (!tag.refine_failure.empty()) json["refine_failure"] = tag.refine_failure;
  return json;
}

// One line per image: the tags, why any kept their quad corners, what the file needed.
void PrintImageLine(const std::string& file, const Detections& found, const ImageNotes& notes, std::ostream& out) {
  out << file << ": " << found.tags.size() << " tags";
  if (!found.rejected.empty()) out << ", " << found.rejected.size() << " rejected";
  out << (found.tags.empty() ? "" : ", ids");
  for (const TagDetection& tag : found.tags) out << " " << tag.id;
  out << "\n";
  for (const TagDetection& tag : found.tags) {
    if (!tag.refine_failure.empty()) out << "  tag " << tag.id << ": quad corners kept: " << tag.refine_failure << "\n";
  }
  if (const std::string note = DescribeImageNotes(notes); !note.empty()) out << "  " << note << "\n";
}

// What one image gave: its JSON entry, its lines of the text form, its
// warnings for stderr. Images are detected in parallel and printed in order.
struct ImageOutcome {
  nlohmann::json json;
  std::string text, warnings;
  int tags = 0;
  bool unreadable = false;
};

ImageOutcome DetectImage(const std::string& file, TagDetector& detector, const DetectorOptions& options,
                         const IdealPixelMap* ideal) {
  ImageOutcome outcome;
  outcome.json = {{"file", file}, {"detections", nlohmann::json::array()}};
  ImageNotes notes;
  StatusOr<cv::Mat> gray = LoadGrayImage(file, &notes);
  if (!gray.ok()) {
    outcome.unreadable = true;
    outcome.json["error"] = gray.status().message();
    outcome.text = gray.status().message() + "\n";  // the message names the file
    return outcome;
  }
  if (ideal && (gray->cols != ideal->width() || gray->rows != ideal->height())) {
    outcome.warnings +=
        "hexcal detect: warning: " + file + " is not the camera's size; edges fitted without distortion\n";
  }
  const Detections found = detector.Detect(*gray);
  for (const TagDetection& tag : found.tags) outcome.json["detections"].push_back(DetectionJson(options.family, tag));
  nlohmann::json rejected = nlohmann::json::array();
  for (const RejectedTag& tag : found.rejected) {
    rejected.push_back({{"id", tag.id}, {"decision_margin", tag.decision_margin}, {"reason", tag.reason}});
  }
  outcome.json["rejected"] = rejected;
  if (const std::string note = DescribeImageNotes(notes); !note.empty()) outcome.json["note"] = note;
  outcome.tags = static_cast<int>(found.tags.size());
  std::ostringstream text;
  PrintImageLine(file, found, notes, text);
  outcome.text = text.str();
  if (std::optional<LayoutHint> other = BetterLayout(*gray, options, found.tags.size())) {
    const std::string hint = DescribeLayoutHint(*other, options);
    outcome.json["hint"] = hint;
    outcome.warnings += "hexcal detect: " + file + ": " + hint + "\n";
  }
  return outcome;
}

// The options with the target's family and border, and the camera's ideal-pixel map, if given.
Status PrepareDetection(const DetectCliOptions& cli, DetectorOptions* options,
                        std::shared_ptr<const IdealPixelMap>* ideal) {
  *options = cli.detector;
  options->refine_edges = !cli.no_refine;
  if (!cli.target.empty()) {
    StatusOr<Target> target = LoadTarget(cli.target);
    if (!target.ok()) return target.status();
    *options = ForTarget(*options, *target);
  }
  if (!cli.camera.empty()) {
    StatusOr<Camera> camera = LoadCamera(cli.camera);
    if (!camera.ok()) return camera.status();
    *ideal = std::make_shared<const IdealPixelMap>(*camera);
  }
  return Status::Ok();
}

int RunDetect(const DetectCliOptions& cli, std::ostream& out, std::ostream& err) {
  DetectorOptions options;
  std::shared_ptr<const IdealPixelMap> ideal;
  if (Status prepared = PrepareDetection(cli, &options, &ideal); !prepared.ok()) {
    return ReportError(err, "detect", prepared);
  }
  StatusOr<std::vector<std::string>> files = ListImages(cli.images);
  if (!files.ok()) return ReportError(err, "detect", files.status());
  const int count = static_cast<int>(files->size());
  // One single-threaded detector per worker: the library's own pool is not
  // safe with more than one thread in libapriltag 3.3 (docs/vision.md).
  StatusOr<std::vector<std::unique_ptr<TagDetector>>> detectors =
      CreateWorkerDetectors(options, ideal, ParallelWorkers(count, cli.threads));
  if (!detectors.ok()) return ReportError(err, "detect", detectors.status());
  std::vector<ImageOutcome> outcomes(files->size());
  ProgressBar progress("detect");
  JobHooks hooks;
  hooks.progress = [&progress](int done, int total) { progress.Update(done, total); };
  ParallelFor(
      count, cli.threads,
      [&](int k, int worker) {
        const size_t index = static_cast<size_t>(k);
        outcomes[index] =
            DetectImage((*files)[index], *(*detectors)[static_cast<size_t>(worker)], options, ideal.get());
      },
      hooks);
  nlohmann::json images = nlohmann::json::array();
  int total_tags = 0, unreadable = 0;
  for (const ImageOutcome& outcome : outcomes) {
    err << outcome.warnings;
    if (!cli.json) out << outcome.text;
    images.push_back(outcome.json);
    total_tags += outcome.tags;
    unreadable += outcome.unreadable ? 1 : 0;
  }
  if (cli.json) {
    out << JsonText(nlohmann::json{{"images", images}});
  } else {
    out << files->size() << " images, " << total_tags << " tags";
    if (unreadable) out << ", " << unreadable << " unreadable";
    out << " (corners: OpenCV pixel convention, " << (options.refine_edges ? "edge-fitted" : "AprilTag's own") << ")\n";
  }
  return kExitOk;
}

}  // namespace

void AddDetectCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<DetectCliOptions>();
  CLI::App* sub = app.add_subcommand("detect", "list the AprilTags found in images");
  sub->add_option("--images", options->images, "an image, or a folder of PNG/JPEG/TIFF images")->required();
  sub->add_option("--family", options->detector.family, "tag family: tag36h11, tag25h9, tag16h5")
      ->capture_default_str();
  sub->add_option("--border-bits", options->detector.border_bits,
                  "black border of the tags in bit cells: 1 (AprilTag) or 2 (Kalibr's aprilgrid)")
      ->check(CLI::Range(1, 2))
      ->capture_default_str();
  CLI::Option* target = sub->add_option("--target", options->target,
                                        "target file or name: take the family and border from it");
  target->excludes(sub->get_option("--family"))->excludes(sub->get_option("--border-bits"));
  sub->add_option("--camera", options->camera, "camera file: fit tag edges in the undistorted image");
  sub->add_option("--min-margin", options->detector.min_decision_margin,
                  "reject decodes with a smaller decision margin (grey levels)")
      ->capture_default_str();
  sub->add_option("--max-hamming", options->detector.max_hamming, "accept at most this many corrected bits (0-2)")
      ->capture_default_str();
  sub->add_option("--threads", options->threads, "images detected in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_flag("--no-refine", options->no_refine, "report AprilTag's own corners (shifted by -0.5 px)");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunDetect(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

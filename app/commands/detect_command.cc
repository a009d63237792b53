// hexcal detect --images DIR|FILE [--target T | --family tag36h11 --border-bits 1] [--camera C] [--no-refine] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "vision/detection.h"
#include "vision/layout_hint.h"
#include "vision/measure.h"

namespace hexcal::cli {
namespace {

struct DetectCliOptions {
  std::string images, camera, target;
  DetectorOptions detector;
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

int RunDetect(const DetectCliOptions& cli, std::ostream& out, std::ostream& err) {
  DetectorOptions options = cli.detector;
  options.refine_edges = !cli.no_refine;
  if (!cli.target.empty()) {
    StatusOr<Target> target = LoadTarget(cli.target);
    if (!target.ok()) return ReportError(err, "detect", target.status());
    options = ForTarget(options, *target);
  }
  std::shared_ptr<const IdealPixelMap> ideal;
  if (!cli.camera.empty()) {
    StatusOr<Camera> camera = LoadCamera(cli.camera);
    if (!camera.ok()) return ReportError(err, "detect", camera.status());
    ideal = std::make_shared<const IdealPixelMap>(*camera);
  }
  StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(options, ideal);
  if (!detector.ok()) return ReportError(err, "detect", detector.status());
  StatusOr<std::vector<std::string>> files = ListImages(cli.images);
  if (!files.ok()) return ReportError(err, "detect", files.status());

  ProgressBar progress("detect");
  nlohmann::json images = nlohmann::json::array();
  int total_tags = 0, unreadable = 0;
  for (size_t i = 0; i < files->size(); ++i) {
    const std::string& file = (*files)[i];
    nlohmann::json image = {{"file", file}, {"detections", nlohmann::json::array()}};
    ImageNotes notes;
    StatusOr<cv::Mat> gray = LoadGrayImage(file, &notes);
    if (!gray.ok()) {
      ++unreadable;
      image["error"] = gray.status().message();
      if (!cli.json) out << gray.status().message() << "\n";  // the message names the file
    } else {
      if (ideal && (gray->cols != ideal->width() || gray->rows != ideal->height())) {
        err << "hexcal detect: warning: " << file << " is not the camera's size; edges fitted without distortion\n";
      }
      const Detections found = (*detector)->Detect(*gray);
      for (const TagDetection& tag : found.tags) image["detections"].push_back(DetectionJson(options.family, tag));
      nlohmann::json rejected = nlohmann::json::array();
      for (const RejectedTag& tag : found.rejected) {
        rejected.push_back({{"id", tag.id}, {"decision_margin", tag.decision_margin}, {"reason", tag.reason}});
      }
      image["rejected"] = rejected;
      if (const std::string note = DescribeImageNotes(notes); !note.empty()) image["note"] = note;
      total_tags += static_cast<int>(found.tags.size());
      if (!cli.json) PrintImageLine(file, found, notes, out);
      if (std::optional<LayoutHint> other = BetterLayout(*gray, options, found.tags.size())) {
        const std::string hint = DescribeLayoutHint(*other, options);
        image["hint"] = hint;
        err << "hexcal detect: " << file << ": " << hint << "\n";
      }
    }
    images.push_back(image);
    progress.Update(static_cast<int>(i + 1), static_cast<int>(files->size()));
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
  sub->add_option("--threads", options->detector.threads, "AprilTag library worker threads for the quad stage "
                  "(more than 1 can crash with libapriltag 3.3: docs/vision.md)")
      ->check(CountRange(1, 64))
      ->capture_default_str();
  sub->add_flag("--no-refine", options->no_refine, "report AprilTag's own corners (shifted by -0.5 px)");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunDetect(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

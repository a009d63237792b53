// hexcal render --camera C --target T --poses poses.csv --out DIR [--seed S] [--noise N] [--blur B]
//               [--occlusion P] [--force] [--json]
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/parallel.h"
#include "vision/image_codecs.h"
#include "vision/renderer.h"

namespace hexcal::cli {
namespace {

// About 0.4 MB a view at 1024 x 768: 5000 views are 2 GB of PNG files.
constexpr size_t kMaxRenderImages = 5000;

struct RenderCliOptions {
  std::string camera = kSimulatedCameraName, target = kDefaultTargetName, poses, out;
  RenderOptions render;
  int threads = 2;  // images rendered at once; 0: every core
  bool force = false, json = false;
};

std::string ViewName(size_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "view_%04zu.png", index);
  return name;
}

int RunRender(const RenderCliOptions& cli, std::ostream& out, std::ostream& err) {
  StatusOr<Camera> camera = LoadCamera(cli.camera);
  if (!camera.ok()) return ReportError(err, "render", camera.status());
  StatusOr<Target> target = LoadTarget(cli.target);
  if (!target.ok()) return ReportError(err, "render", target.status());
  StatusOr<std::vector<Vector6d>> vectors = LoadPoses(cli.poses);
  if (!vectors.ok()) return ReportError(err, "render", vectors.status());
  if (vectors->size() > kMaxRenderImages) {
    return ReportError(err, "render",
                       Status::BadInput(cli.poses + ": " + std::to_string(vectors->size()) + " poses, more than the " +
                                        std::to_string(kMaxRenderImages) + " images render writes at once"));
  }
  std::string error;
  if (!cli.render.IsValid(&error)) return ReportError(err, "render", Status::BadInput(error));
  namespace fs = std::filesystem;
  const fs::path folder(cli.out);
  const std::string truth_path = (folder / "ground_truth.csv").string();
  if (Status s = CheckOutputFree(truth_path, cli.force); !s.ok()) return ReportError(err, "render", s);
  if (Status s = CreateFolders(cli.out); !s.ok()) return ReportError(err, "render", s);

  const Renderer renderer(*camera, *target, cli.render);
  std::vector<RenderedView> views(vectors->size());
  std::vector<Status> written(vectors->size());
  ProgressBar progress("render");
  ParallelFor(static_cast<int>(vectors->size()), cli.threads,
              [&](int index, int) {
                const Pose pose = PoseFromVector((*vectors)[static_cast<size_t>(index)], EulerConvention::kXYZ);
                RenderedView view = renderer.Render(pose, static_cast<uint64_t>(index));
                StatusOr<std::string> png = EncodePng(view.image);
                written[static_cast<size_t>(index)] =
                    png.ok() ? WriteFileAtomically((folder / ViewName(static_cast<size_t>(index))).string(), *png)
                             : png.status();
                view.image.release();
                views[static_cast<size_t>(index)] = std::move(view);
              },
              {[&](int done, int total) { progress.Update(done, total); }});
  for (const Status& s : written) {
    if (!s.ok()) return ReportError(err, "render", s);
  }
  std::vector<std::vector<std::string>> truth, corners;
  int visible = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    std::vector<std::string> row = {ViewName(i)};
    const Vector6d v = VectorFromPose(views[i].camera_from_target, EulerConvention::kXYZ);
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
    truth.push_back(row);
    for (const ProjectedCorner& c : views[i].corners) {
      if (!c.pixel.allFinite()) continue;
      corners.push_back({ViewName(i), std::to_string(c.tag_id), std::to_string(c.corner), FormatNumber(c.pixel.x()),
                         FormatNumber(c.pixel.y()), c.visible ? "1" : "0"});
      visible += c.visible;
    }
  }
  if (Status s =
          WriteCsv((folder / "corners.csv").string(), {"file", "tag_id", "corner", "u", "v", "visible"}, corners);
      !s.ok()) {
    return ReportError(err, "render", s);
  }
  if (Status s = WriteCsv(truth_path, {"file", "x", "y", "z", "q1", "q2", "q3"}, truth); !s.ok()) {
    return ReportError(err, "render", s);
  }
  if (cli.json) {
    out << JsonText(nlohmann::json{{"images", views.size()},
                                   {"out", cli.out},
                                   {"seed", cli.render.seed},
                                   {"visible_corners", visible},
                                   {"ground_truth", truth_path}});
  } else {
    out << views.size() << " images written to " << cli.out << " (" << camera->width << " x " << camera->height
        << ", seed " << cli.render.seed << "); ground truth in " << truth_path << " and corners.csv\n";
  }
  return kExitOk;
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RenderCliOptions>();
  CLI::App* sub = app.add_subcommand("render", "draw synthetic images of the target at given poses");
  sub->add_option("--camera", options->camera, "camera file, or the built-in name sim-4.2mm-1024x768")
      ->capture_default_str();
  sub->add_option("--target", options->target, "target YAML file or the built-in name aprilgrid-6x6")
      ->capture_default_str();
  sub->add_option("--poses", options->poses, "CSV of camera_from_target poses x,y,z,q1,q2,q3 (target unit, deg)")
      ->required();
  sub->add_option("--out", options->out, "output folder")->required();
  sub->add_option("--seed", options->render.seed, "noise and lighting seed")->capture_default_str();
  sub->add_option("--noise", options->render.noise_sigma, "read noise, grey levels")->capture_default_str();
  sub->add_option("--blur", options->render.blur_sigma_px, "optical blur sigma, pixels")->capture_default_str();
  sub->add_option("--occlusion", options->render.occlusion_probability, "chance of an occluder per image (0-1)")
      ->capture_default_str();
  sub->add_option("--threads", options->threads, "images rendered in parallel (0 = every core)")
      ->check(CountRange(0, kMaxThreads))
      ->capture_default_str();
  sub->add_flag("--force", options->force, "overwrite an existing ground truth in the folder");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunRender(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

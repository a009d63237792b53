// hexcal session init --robot R --camera C --target T DIR [--noise-position p]
//   [--noise-angle a] [--noise-leg l] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::cli {
namespace {

struct SessionInitOptions {
  std::string dir;
  SessionConfig config;
  bool json = false;
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-*
};

int RunSessionInit(SessionInitOptions cli, std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *cli.noise, &cli.config.noise, "noise"); !s.ok())
    return ReportError(err, "session init", s);
  // Check that the names load now rather than at the first calibration.
  if (StatusOr<Robot> robot = LoadRobot(cli.config.robot); !robot.ok())
    return ReportError(err, "session init", robot.status());
  if (StatusOr<Camera> camera = LoadCamera(cli.config.camera); !camera.ok())
    return ReportError(err, "session init", camera.status());
  if (StatusOr<Target> target = LoadTarget(cli.config.target); !target.ok())
    return ReportError(err, "session init", target.status());
  if (Status s = InitSession(cli.dir, cli.config); !s.ok()) return ReportError(err, "session init", s);
  const SessionPaths paths(cli.dir);
  if (cli.json) {
    out << nlohmann::json{{"session", cli.dir}, {"config", paths.config}, {"images", paths.images}}.dump(2) << "\n";
  } else {
    out << "session " << cli.dir << ": wrote " << paths.config << "; put the images in " << paths.images
        << " and their readings in " << paths.legs << " (image,L1..L6,holdout)\n";
  }
  return kExitOk;
}

}  // namespace

void AddSessionCommand(CLI::App& app, int* exit_code) {
  CLI::App* session = app.add_subcommand("session", "create a session folder (docs/session.md)");
  session->require_subcommand(1);
  auto options = std::make_shared<SessionInitOptions>();
  CLI::App* init = session->add_subcommand("init", "create DIR with session.yaml, images/ and results/");
  init->add_option("dir", options->dir, "session folder")->required();
  init->add_option("--robot", options->config.robot, "nominal robot file or preset name")->required();
  init->add_option("--camera", options->config.camera, "camera file (hexcal intrinsics)")->required();
  init->add_option("--target", options->config.target, "target file or name")->required();
  AddOptionFlags(init, NoiseModelOptions(), options->noise, "noise-");
  init->add_flag("--json", options->json, "print one JSON object on stdout");
  init->callback([=] { *exit_code = RunSessionInit(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

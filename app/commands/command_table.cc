#include "app/commands/command_table.h"

#include "app/commands/cli_common.h"
#include "app/commands/help_examples.h"

namespace hexcal::cli {

namespace {
constexpr CommandEntry kCommands[] = {
    {"robot", AddRobotCommand},           {"ik", AddIkCommand},           {"fk", AddFkCommand},
    {"candidates", AddCandidatesCommand}, {"indices", AddIndicesCommand}, {"demo", AddDemoCommand},
    {"plan", AddPlanCommand},
    {"calibrate", AddCalibrateCommand},
    {"validate", AddValidateCommand},
    {"simulate", AddSimulateCommand},
    {"study", AddStudyCommand},
    {"target", AddTargetCommand},
    {"detect", AddDetectCommand},
    {"render", AddRenderCommand},
    {"intrinsics", AddIntrinsicsCommand},
    {"measure", AddMeasureCommand},
    {"session", AddSessionCommand},
    {"report", AddReportCommand},
    {"acquire", AddAcquireCommand},
    {"verify", AddVerifyCommand},
    {"sim-camera", AddSimCameraCommand},
    {"export", AddExportCommand},
    {"camera", AddCameraCommand},
};
}  // namespace

void AddAllCommands(CLI::App& app, int* exit_code) {
  for (const CommandEntry& entry : kCommands) entry.add(app, exit_code);
  AddHelpExamples(app);
  app.require_subcommand(1);
}

int RunHexcal(int argc, const char* const* argv) {
  CLI::App app{"hexcal: pose planning and calibration for Gough-Stewart platforms"};
  app.set_version_flag("--version", "hexcal 0.1.0");
  int exit_code = kExitOk;
  AddAllCommands(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  return exit_code;
}

}  // namespace hexcal::cli

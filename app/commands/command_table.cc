#include "app/commands/command_table.h"

#include <iostream>
#include <string>

#include "app/commands/cli_common.h"
#include "app/commands/terminal_text.h"
#include "app/commands/help_examples.h"
#include "vision/library_logs.h"

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

// Every numeric option of `app` and its subcommands, whoever declared it,
// takes plain decimal text (DecimalNumber); the command's own checks run first.
void RequireDecimalNumbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_max() == 0) continue;  // a flag: its values are true/false, not numbers
    const std::string type = option->get_type_name();
    const std::string base = type.substr(0, type.find(':'));  // then its checks' descriptions
    if (base == "INT" || base == "UINT" || base == "FLOAT") option->check(DecimalNumber(base));
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) RequireDecimalNumbers(*sub);
}

// "session record" when the error came while parsing that subcommand; "" before any.
std::string ParsedCommand(const CLI::App& app) {
  std::string path;
  for (const CLI::App* level = &app; !level->get_subcommands().empty();) {
    level = level->get_subcommands().front();
    path += (path.empty() ? "" : " ") + level->get_name();
  }
  return path;
}

// `hexcal --verbose COMMAND ...`: the flag comes before the command.
bool VerboseAsked(int argc, const char* const* argv) {
  for (int k = 1; k < argc && argv[k][0] == '-'; ++k)
    if (std::string(argv[k]) == "--verbose") return true;
  return false;
}

}  // namespace

void AddAllCommands(CLI::App& app, int* exit_code) {
  for (const CommandEntry& entry : kCommands) entry.add(app, exit_code);
  AddHelpExamples(app);
  app.require_subcommand(1);
  RequireDecimalNumbers(app);
}

int RunHexcal(int argc, const char* const* argv) {
  CLI::App app{"hexcal: pose planning and calibration for Gough-Stewart platforms"};
  app.set_version_flag("--version", "hexcal 0.1.0");
  app.add_flag("--verbose",
               "before the command: let the libraries' own messages (OpenCV's, FFmpeg's, GStreamer's, Aravis') "
               "through to stderr");
  // hexcal says what failed in its own words; the libraries' log lines only
  // repeat it, or are noise (vision/library_logs.h).
  ShowLibraryLogs(VerboseAsked(argc, argv));
  int exit_code = kExitOk;
  AddAllCommands(app, &exit_code);
  const TerminalEscaping escaping;  // names from files never reach the terminal raw
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? kExitOk : kExitBadInput;  // --help, --version
    // Every error of every command starts "hexcal <command>:", CLI11's too.
    const std::string command = ParsedCommand(app);
    const std::string prefix = command.empty() ? "hexcal" : "hexcal " + command;
    std::cerr << prefix << ": " << e.what() << "\nRun '" << prefix << " --help' for the options.\n";
    return kExitBadInput;
  }
  return exit_code;
}

}  // namespace hexcal::cli

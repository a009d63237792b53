// The table of `hexcal` subcommands. Each entry adds its CLI11 subcommand and
// binds its options; the callback runs the command's typed Run function (which
// tests call directly) and stores the exit code.
#pragma once

#include <CLI/CLI.hpp>

namespace hexcal::cli {

struct CommandEntry {
  const char* name;
  void (*add)(CLI::App& app, int* exit_code);
};

void AddRobotCommand(CLI::App& app, int* exit_code);
void AddIkCommand(CLI::App& app, int* exit_code);
void AddFkCommand(CLI::App& app, int* exit_code);
void AddCandidatesCommand(CLI::App& app, int* exit_code);
void AddIndicesCommand(CLI::App& app, int* exit_code);
void AddDemoCommand(CLI::App& app, int* exit_code);
void AddPlanCommand(CLI::App& app, int* exit_code);
void AddCalibrateCommand(CLI::App& app, int* exit_code);
void AddValidateCommand(CLI::App& app, int* exit_code);
void AddSimulateCommand(CLI::App& app, int* exit_code);
void AddStudyCommand(CLI::App& app, int* exit_code);
void AddTargetCommand(CLI::App& app, int* exit_code);
void AddDetectCommand(CLI::App& app, int* exit_code);
void AddRenderCommand(CLI::App& app, int* exit_code);
void AddIntrinsicsCommand(CLI::App& app, int* exit_code);
void AddMeasureCommand(CLI::App& app, int* exit_code);
void AddSessionCommand(CLI::App& app, int* exit_code);
void AddReportCommand(CLI::App& app, int* exit_code);
void AddAcquireCommand(CLI::App& app, int* exit_code);
void AddSimCameraCommand(CLI::App& app, int* exit_code);
void AddVerifyCommand(CLI::App& app, int* exit_code);
void AddExportCommand(CLI::App& app, int* exit_code);
void AddCameraCommand(CLI::App& app, int* exit_code);

// Builds the whole `hexcal` application; `exit_code` receives the command's code.
void AddAllCommands(CLI::App& app, int* exit_code);

// Runs `hexcal` with argv as a user would: parse, run, return the exit code.
int RunHexcal(int argc, const char* const* argv);

}  // namespace hexcal::cli

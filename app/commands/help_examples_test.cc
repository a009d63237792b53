// Every `hexcal ... --help` teaches by example, and --threads means the same
// everywhere (issue 39). The commands are walked from the application itself,
// so a command added without an example fails here.
#include "app/commands/help_examples.h"

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "app/commands/command_table.h"

namespace hexcal::cli {
namespace {

// Every subcommand of `app`, at every depth.
std::vector<CLI::App*> AllCommands(CLI::App& app) {
  std::vector<CLI::App*> commands;
  std::function<void(CLI::App&)> walk = [&](CLI::App& parent) {
    for (CLI::App* sub : parent.get_subcommands({})) {
      commands.push_back(sub);
      walk(*sub);
    }
  };
  walk(app);
  return commands;
}

class HexcalHelp : public ::testing::Test {
 protected:
  HexcalHelp() { AddAllCommands(app_, &exit_code_); }
  CLI::App app_{"hexcal"};
  int exit_code_ = 0;
};

TEST_F(HexcalHelp, EveryCommandsHelpEndsInAnExampleOfThatCommand) {
  const std::vector<CLI::App*> commands = AllCommands(app_);
  ASSERT_GT(commands.size(), 25u);  // 23 commands and the actions of robot, session, target, camera
  for (CLI::App* command : commands) {
    const std::string path = CommandPath(*command);
    const std::string help = command->help();
    EXPECT_NE(help.find("Example:\n  hexcal " + path + " "), std::string::npos)
        << "hexcal " << path << " --help has no example of itself:\n"
        << help;
  }
}

TEST_F(HexcalHelp, EveryExampleIsOfACommandThatExists) {
  std::set<std::string> paths;
  for (CLI::App* command : AllCommands(app_)) paths.insert(CommandPath(*command));
  for (const auto& [path, example] : HelpExamples()) {
    EXPECT_TRUE(paths.count(path)) << "an example for 'hexcal " << path << "', which is no command";
  }
}

// One meaning of --threads: how many items run at once, 0 for every core
// (docs/cli.md); never a library's internal threads.
TEST_F(HexcalHelp, ThreadsMeansTheSameEverywhere) {
  int with_threads = 0;
  for (CLI::App* command : AllCommands(app_)) {
    const CLI::Option* threads = command->get_option_no_throw("--threads");
    if (threads == nullptr) continue;
    ++with_threads;
    EXPECT_NE(threads->get_description().find("0 = every core"), std::string::npos)
        << "hexcal " << CommandPath(*command) << " --threads: " << threads->get_description();
  }
  EXPECT_EQ(with_threads, 7);  // plan, simulate, study, detect, render, intrinsics, measure
}

}  // namespace
}  // namespace hexcal::cli

// The example at the foot of every `hexcal ... --help` (issue 39): one table
// of command lines, most of them runnable after the README's
// `hexcal demo --out example`.
//
//   CLI::App app;
//   AddAllCommands(app, &exit_code);         // calls AddHelpExamples(app) last
//   HelpExamples().at("session record");     // "hexcal session record run1 --image ..."
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <string>

namespace hexcal::cli {

// Command path below `hexcal` ("plan", "camera convert") -> its example.
const std::map<std::string, std::string>& HelpExamples();

// "session record" for the subcommand `record` of `session`.
std::string CommandPath(const CLI::App& command);

// Sets the "Example:" footer of every subcommand of `app`, at every depth.
void AddHelpExamples(CLI::App& app);

}  // namespace hexcal::cli

// Helpers shared by the `hexcal` commands: exit codes, error reporting,
// JSON forms of core types, progress on a terminal.
#pragma once

#include <CLI/CLI.hpp>
#include <iosfwd>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/atomic_file.h"
#include "core/constraints.h"
#include "core/job_hooks.h"
#include "core/observability.h"
#include "core/option_spec.h"
#include "core/robot.h"
#include "core/status.h"
#include "session/json_forms.h"

namespace hexcal::cli {

// Exit codes of every command, one per tier of core/status.h (docs/cli.md,
// "Exit codes").
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // the computation failed (no convergence, too few usable poses), a cancel
constexpr int kExitBadInput = 2;  // an option, a value, a file's contents or a path is wrong
constexpr int kExitBusy = 3;      // the session is in use by another writer: try again, or --wait
constexpr int kExitIo = 4;        // the disk, a device or the network refused: permissions, full, unplugged

// The one mapping of a status's kind to an exit code (docs/cli.md).
int ExitCodeFor(const Status& status);

// Prints "hexcal <command>: <message>" on err and returns ExitCodeFor(status).
int ReportError(std::ostream& err, const std::string& command, const Status& status);

// The flag of each option key a command takes from an option table
// (AddOptionFlags in option_flags.h records them).
using OptionFlagNames = std::map<std::string, std::string>;

// `status` in the CLI's words: an error about an option of `flags`
// (Status::option(), its key) names the option by its flag, "--settle: must
// be at most 600 s, got 900", as CLI11 refuses the flag itself.
Status InFlagWords(const Status& status, const OptionFlagNames& flags);

// ReportError of InFlagWords(status, flags).
int ReportError(std::ostream& err, const std::string& command, const Status& status, const OptionFlagNames& flags);

// The text of every --json object: indented, one line feed after it. Invalid
// UTF-8 (a Latin-1 file name, a controller's greeting) becomes U+FFFD, as in
// the session's manifest, instead of nlohmann's type_error.316 and an abort
// after the work was done (issue 36); control characters come out as \uXXXX.
std::string JsonText(const nlohmann::json& json);

using workflow::IndicesJson;
using workflow::PoseJson;
using workflow::RobotJson;

// Bounds of the count options (issue 13, bounded input): a typo such as
// --poses 100000 must stop at once, not start writing 38 GB of images.
// --threads of every command: 0 to kMaxThreads (core/option_spec.h).

// A CLI11 check for an integer option in [min, max]; `why` says what the bound
// protects, e.g. "each pose is a rendered image".
CLI::Validator CountRange(long long min, long long max, const std::string& why = "");

// CLI11 reads integers with strtoll in base 0 ("0x10" is 16, "010" is 8, "-1"
// a huge unsigned, overflow saturates) and floats with strtold (hex floats,
// "nan", 1e400 as inf). This check takes plain decimal text only, for an
// option of CLI11 type `type` ("INT", "UINT" or "FLOAT"), and says what is
// wrong with anything else; AddAllCommands puts it on every numeric option.
CLI::Validator DecimalNumber(const std::string& type);

// "1.5,2,3,..." -> exactly `count` finite numbers.
StatusOr<std::vector<double>> ParseNumberList(const std::string& text, int count, const std::string& what);

// A one-line progress bar on stderr when it is a terminal; silent otherwise.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void Update(int done, int total);

 private:
  std::string label_;
  bool enabled_;
  int last_percent_ = -1;
};

// JobHooks for a command on a terminal: each stage gets its own progress bar
// (labelled with the stage, or `label` before the first stage); notes go to `log`.
class TerminalJob {
 public:
  explicit TerminalJob(std::string label = "", std::ostream* log = nullptr);
  // The hooks' callbacks point at this object: it stays where it was made.
  TerminalJob(const TerminalJob&) = delete;
  TerminalJob& operator=(const TerminalJob&) = delete;
  const JobHooks& hooks() const { return hooks_; }

 private:
  std::unique_ptr<ProgressBar> bar_;
  JobHooks hooks_;
};

}  // namespace hexcal::cli

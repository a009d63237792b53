// Helpers shared by the `hexcal` commands: exit codes, error reporting,
// JSON forms of core types, progress on a terminal.
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "core/constraints.h"
#include "core/observability.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::cli {

// Exit codes of every command.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // the computation failed (no convergence, ...)
constexpr int kExitBadInput = 2;  // a file or an option is wrong

// Prints "hexcal <command>: <message>" on err and returns `code`.
int ReportError(std::ostream& err, const std::string& command, const Status& status, int code = kExitBadInput);

nlohmann::json PoseJson(const Robot& robot, const Pose& pose);
nlohmann::json IndicesJson(const ObservabilityIndices& indices);
nlohmann::json RobotJson(const Robot& robot);

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

}  // namespace hexcal::cli

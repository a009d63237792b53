// Where a session stands, step by step, from the files' contents (`hexcal
// session status DIR`; docs/session.md, "Status"): each step done, stale (an
// input changed since it ran: by SHA-256, not file times), to do, or broken
// (a file that does not load), with a sentence saying what and what next.
//
//   StatusOr<SessionStatus> status = ReadSessionStatus("run1");
//   std::cout << FormatSessionStatus(*status);
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "session/session_results.h"

namespace hexcal::workflow {

enum class StepStatus { kDone, kStale, kTodo, kBroken };
const char* StepStatusName(StepStatus status);  // "done", "stale", "todo", "broken"

struct StepReport {
  std::string step;  // "robot", "plan", "readings", "measure", "calibrate", "validate"
  StepStatus status = StepStatus::kTodo;
  std::string detail;  // "24 poses", "legs.csv changed since the results (2026-12-01T04:12:09Z)"
};

struct SessionStatus {
  std::string session;
  std::vector<StepReport> steps;

  const StepReport* Find(const std::string& step) const;  // nullptr for an unknown name
};

// Reads only; a session whose session.yaml does not load is an error.
StatusOr<SessionStatus> ReadSessionStatus(const std::string& session_dir);
// The same, also handing back results/ as it was loaded to judge it (or why
// not), and the session's input hashes (HashSessionInputs) when `inputs` is
// given, so that a caller showing the results or the study
// (session_study.h) does not hash every input twice.
StatusOr<SessionStatus> ReadSessionStatus(const std::string& session_dir, StatusOr<SessionResults>* results,
                                          StatusOr<ContentHashes>* inputs = nullptr);
nlohmann::json ToJson(const SessionStatus& status);
std::string FormatSessionStatus(const SessionStatus& status);

}  // namespace hexcal::workflow

#include "session/results_files.h"

#include <filesystem>

#include "core/session.h"

namespace hexcal::workflow {

std::string ResultsFile(const std::string& session_dir, const char* name) {
  return (std::filesystem::path(SessionPaths(session_dir).results) / name).string();
}

std::string ResultsName(const char* name) { return std::string("results/") + name; }

}  // namespace hexcal::workflow

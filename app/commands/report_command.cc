// hexcal report --session DIR --out report.html [--force]
//
// One self-contained HTML page from a calibrated session (app/commands/session_report.h).
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/session_report.h"
#include "core/atomic_file.h"

namespace hexcal::cli {
namespace {

namespace fs = std::filesystem;

struct ReportCliOptions {
  std::string session, out;
  bool force = false;
};

int RunReport(const ReportCliOptions& cli, std::ostream& out, std::ostream& err) {
  std::error_code exists_error;
  if (!cli.force && fs::exists(cli.out, exists_error))
    return ReportError(err, "report", Status::Error(cli.out + ": exists; use --force to overwrite it"));
  StatusOr<std::string> html = SessionReportHtml(cli.session);
  if (!html.ok()) return ReportError(err, "report", html.status());
  if (Status s = WriteFileAtomically(cli.out, *html); !s.ok()) return ReportError(err, "report", s, kExitFailure);
  out << "report of " << cli.session << " written to " << cli.out << "\n";
  return kExitOk;
}

}  // namespace

void AddReportCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ReportCliOptions>();
  CLI::App* sub = app.add_subcommand("report", "one self-contained HTML page of a calibrated session");
  sub->add_option("--session", options->session, "session folder (after calibrate --session)")->required();
  sub->add_option("--out", options->out, "HTML file to write")->required();
  sub->add_flag("--force", options->force, "overwrite --out if it exists");
  sub->callback([=] { *exit_code = RunReport(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

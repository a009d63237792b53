// hexcal report --session DIR --out report.html [--force] [--json]
//
// One self-contained HTML page from a calibrated session (report/session_report.h).
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "report/calibration_verdict.h"
#include "report/session_report.h"

namespace hexcal::cli {
namespace {

int RunReport(const workflow::ReportRequest& request, bool json, std::ostream& out, std::ostream& err) {
  StatusOr<std::string> written = workflow::WriteSessionReport(request);
  if (!written.ok()) return ReportError(err, "report", written.status());
  if (json) {
    out << JsonText({{"session", request.session}, {"out", *written}});
    return kExitOk;
  }
  out << "report of " << request.session << " written to " << *written << "\n";
  // The page was made from this report: it loads.
  StatusOr<workflow::CalibrationReport> report =
      workflow::LoadCalibrationReport(workflow::CalibrationReportPath(request.session));
  if (report.ok()) out << workflow::MakeVerdict(*report).ToText();
  return kExitOk;
}

}  // namespace

void AddReportCommand(CLI::App& app, int* exit_code) {
  auto request = std::make_shared<workflow::ReportRequest>();
  CLI::App* sub = app.add_subcommand("report", "one self-contained HTML page of a calibrated session");
  sub->add_option("--session", request->session, "session folder (after calibrate --session)")->required();
  sub->add_option("--out", request->out, "HTML file to write")->required();
  auto json = std::make_shared<bool>(false);
  sub->add_flag("--force", request->force, "overwrite --out if it exists");
  sub->add_flag("--json", *json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunReport(*request, *json, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

// hexcal report --session DIR --out report.html [--force]
//
// One self-contained HTML page from a calibrated session (docs/session.md):
// the registration, the calibrated parameters with σ and their change from
// nominal, measurement quality per image, validation errors before and after.
// Charts are inline SVG (app/plots/svg_chart.h); nothing is fetched.
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/plots/svg_chart.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/session.h"

namespace hexcal::cli {
namespace {

namespace fs = std::filesystem;

struct ReportCliOptions {
  std::string session, out;
  bool force = false;
};

std::string Escape(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '<')
      escaped += "&lt;";
    else if (c == '>')
      escaped += "&gt;";
    else if (c == '&')
      escaped += "&amp;";
    else
      escaped += c;
  }
  return escaped;
}

std::string Number(const nlohmann::json& value) {
  if (!value.is_number()) return "–";
  std::ostringstream out;
  out.precision(4);
  out << value.get<double>();
  return out.str();
}

// Per-image reprojection RMS (px) of measurements.csv, in file order.
plots::LineSeries MeasurementRms(const std::string& path) {
  plots::LineSeries series{"reprojection RMS", {}, {}};
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return series;
  StatusOr<int> rms = ColumnIndex(*table, "rms_px");
  if (!rms.ok()) return series;
  for (size_t r = 0; r < table->rows.size(); ++r) {
    StatusOr<double> value = NumberAt(*table, r, *rms);
    if (!value.ok()) continue;
    series.x.push_back(static_cast<double>(r + 1));
    series.y.push_back(*value);
  }
  return series;
}

std::string ParameterTable(const nlohmann::json& parameters, const std::string& unit) {
  std::string html =
      "<table><tr><th>leg</th><th>parameter</th><th>nominal</th><th>calibrated</th><th>change</th>"
      "<th>&sigma;</th></tr>\n";
  for (const nlohmann::json& p : parameters) {
    const double change = p["estimate"].get<double>() - p["nominal"].get<double>();
    html += "<tr><td>" + std::to_string(p["leg"].get<int>()) + "</td><td>" + p["name"].get<std::string>() +
            "</td><td>" + Number(p["nominal"]) + "</td><td>" + Number(p["estimate"]) + "</td><td>" + Number(change) +
            "</td><td>" + Number(p["sigma"]) + "</td></tr>\n";
  }
  return html + "</table><p>Lengths in " + Escape(unit) + ".</p>\n";
}

StatusOr<std::string> ReportHtml(const std::string& dir) {
  const SessionPaths paths(dir);
  const std::string json_path = (fs::path(paths.results) / "report.json").string();
  StatusOr<std::string> text = ReadFileToString(json_path);
  if (!text.ok()) return Status::Error(text.status().message() + " (run hexcal calibrate --session first)");
  nlohmann::json report;
  try {
    report = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& e) {
    return Status::Error(json_path + ": " + e.what());
  }
  const std::string unit = report.value("length_unit", "");
  std::string html =
      "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>hexcal session report</title><style>"
      "body{font-family:sans-serif;max-width:900px;margin:2em auto}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}</style></head><body>\n";
  html += "<h1>Session " + Escape(dir) + "</h1>\n<p>" + std::to_string(report["images"].get<int>()) +
          " images: " + std::to_string(report["calibration_images"].get<int>()) + " for calibration, " +
          std::to_string(report["held_out_images"].get<int>()) + " held out, " +
          std::to_string(report["unusable_images"].get<int>()) + " without a usable target pose.</p>\n";
  const nlohmann::json& reg = report["registration"];
  html += "<h2>Registration</h2><p>Closure |A&middot;Y &minus; X&middot;B| with the nominal robot: RMS " +
          Number(reg["position_rms"]) + " " + Escape(unit) + ", " + Number(reg["angle_rms_deg"]) +
          "&deg;; with the calibrated robot: " + Number(report["closure_after_calibration"]["position_rms"]) + " " +
          Escape(unit) + ", " + Number(report["closure_after_calibration"]["angle_rms_deg"]) + "&deg;.</p>\n";

  plots::ChartOptions quality;
  quality.title = "Measurement quality";
  quality.x_label = "image (measurements.csv order)";
  quality.y_label = "reprojection RMS (px)";
  const plots::LineSeries rms = MeasurementRms(paths.measurements);
  if (!rms.x.empty()) html += "<h2>Measurements</h2>\n" + plots::LineChartSvg(quality, {rms}) + "\n";

  const nlohmann::json& validation = report["validation"];
  if (validation.is_object()) {
    plots::ChartOptions chart;
    chart.title = "Held-out validation (forward kinematics against the camera)";
    chart.y_label = "RMS error";
    chart.log_y = true;
    std::vector<plots::Bar> bars = {
        {"position before (" + unit + ")", validation["before"]["position_rms"].get<double>(), 0},
        {"position after (" + unit + ")", validation["after"]["position_rms"].get<double>(), 0},
        {"orientation before (deg)", validation["before"]["orientation_rms"].get<double>(), 0},
        {"orientation after (deg)", validation["after"]["orientation_rms"].get<double>(), 0}};
    html += "<h2>Validation</h2>\n" + plots::BarChartSvg(chart, bars) + "\n";
  }

  plots::ChartOptions change;
  change.title = "Calibrated minus nominal, with 1 sigma";
  change.x_label = "parameter (leg, name)";
  change.y_label = "change (" + unit + ")";
  change.width = 900;
  std::vector<plots::Bar> changes;
  for (const nlohmann::json& p : report["parameters"]) {
    const double sigma = p["sigma"].is_number() ? p["sigma"].get<double>() : 0;
    changes.push_back({std::to_string(p["leg"].get<int>()) + p["name"].get<std::string>(),
                       p["estimate"].get<double>() - p["nominal"].get<double>(), sigma});
  }
  html += "<h2>Calibrated parameters</h2>\n" + plots::BarChartSvg(change, changes) + "\n" +
          ParameterTable(report["parameters"], unit);
  return html + "</body></html>\n";
}

int RunReport(const ReportCliOptions& cli, std::ostream& out, std::ostream& err) {
  std::error_code exists_error;
  if (!cli.force && fs::exists(cli.out, exists_error))
    return ReportError(err, "report", Status::Error(cli.out + ": exists; use --force to overwrite it"));
  StatusOr<std::string> html = ReportHtml(cli.session);
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

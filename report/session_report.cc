#include "report/session_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "charts/chart_render.h"
#include "charts/figures.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/measurements.h"
#include "core/observability.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "report/calibration_verdict.h"
#include "report/corner_report_section.h"
#include "report/html_text.h"
#include "report/pixel_report_section.h"
#include "report/study_report_section.h"
#include "session/calibration_report.h"
#include "session/camera_frame_diagnosis.h"
#include "session/results_files.h"
#include "session/session_models.h"
#include "session/session_results.h"
#include "vision/camera.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

std::string Escape(const std::string& text) { return HtmlEscape(text); }

// 4 significant digits.
std::string Figure(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

// 3 significant digits.
std::string FigureOf3(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

std::string Number(const std::optional<double>& value) { return value ? Figure(*value) : "–"; }

// A chart inline (charts/figures.h); a chart that cannot be drawn leaves its
// reason in the page rather than failing the whole report.
std::string ChartHtml(const charts::ChartSpec& spec) {
  StatusOr<std::string> svg = charts::ChartSvgElement(spec);
  return svg.ok() ? *svg + "\n" : "<p>Chart not drawn: " + Escape(svg.status().message()) + "</p>\n";
}

// Per-image reprojection RMS (px) of camera_poses.csv, in file order.
std::vector<double> MeasurementRms(const std::string& path) {
  std::vector<double> rms_px;
  StatusOr<CsvTable> table = ReadCsv(path);
  if (!table.ok()) return rms_px;
  StatusOr<int> rms = ColumnIndex(*table, "rms_px");
  if (!rms.ok()) return rms_px;
  for (size_t r = 0; r < table->rows.size(); ++r) {
    StatusOr<double> value = NumberAt(*table, r, *rms);
    if (value.ok()) rms_px.push_back(*value);
  }
  return rms_px;
}

// |change|/σ as a word of identification, not an alarm (docs/calibration.md, "Verdict").
std::string IdentifiedCell(const ParameterEstimate& p) {
  if (!p.sigma || *p.sigma <= 0) return "–";
  const double ratio = std::abs(p.estimate - p.nominal) / *p.sigma;
  return (ratio > 3 ? "yes, " : "no, ") + FigureOf3(ratio) + "&sigma;";
}

std::string ParameterTable(const std::vector<ParameterEstimate>& parameters, const std::string& unit) {
  const std::string u = Escape(unit);
  std::string html = "<table><tr><th>leg</th><th>parameter</th><th>nominal (" + u + ")</th><th>calibrated (" + u +
                     ")</th><th>change (" + u + ")</th><th>&sigma; (" + u +
                     ")</th><th>identified (change &#8811; &sigma;)</th></tr>\n";
  for (const ParameterEstimate& p : parameters) {
    const double change = p.estimate - p.nominal;
    html += "<tr><td>" + std::to_string(p.leg) + "</td><td>" + Escape(p.name) + "</td><td>" + Figure(p.nominal) +
            "</td><td>" + Figure(p.estimate) + "</td><td>" + Figure(change) + "</td><td>" + Number(p.sigma) +
            "</td><td>" + IdentifiedCell(p) + "</td></tr>\n";
  }
  return html +
         "</table><p>Identified: the change is more than 3&sigma; (the figure is |change|/&sigma;): the "
         "calibration determined that parameter and found it differs from nominal. That is what a calibration is "
         "for, not an alarm; the verdict above says whether the &sigma; themselves are small enough.</p>\n";
}

// The box the page opens with: the level in its colour, then one row per finding.
std::string VerdictBox(const Verdict& verdict) {
  std::string html = "<div class=\"verdict\" style=\"border-color:" + std::string(VerdictLevelColour(verdict.level)) +
                     "\"><h2>Verdict: <span style=\"color:" + VerdictLevelColour(verdict.level) + "\">" +
                     VerdictLevelName(verdict.level) +
                     "</span></h2>\n<table><tr><th>aspect</th><th>level</th><th>figure</th><th>threshold</th>"
                     "<th>meaning</th><th>advice</th></tr>\n";
  // What needs action first; the text and JSON forms keep the fixed order.
  std::vector<Finding> findings = verdict.findings;
  std::stable_sort(findings.begin(), findings.end(),
                   [](const Finding& a, const Finding& b) { return a.level > b.level; });
  for (const Finding& f : findings) {
    html += "<tr><td>" + Escape(f.aspect) + "</td><td style=\"color:" + VerdictLevelColour(f.level) +
            ";font-weight:bold\">" + VerdictLevelName(f.level) + "</td><td>" + Escape(f.figure) + "</td><td>" +
            Escape(f.threshold) + "</td><td>" + Escape(f.meaning) + "</td><td>" +
            (f.advice.empty() ? "–" : Escape(f.advice)) + "</td></tr>\n";
  }
  return html + "</table></div>\n";
}

// "O1 4.3 cm (the volume of ...), O2 0.012 (sigma_min / sigma_max: ...), ...":
// each index with its unit and meaning (core/observability.h).
std::string IndexItems(const ObservabilityIndices& o, const std::string& unit) {
  const double values[] = {o.o1, o.o2, o.o3, o.o4};
  std::string items;
  for (int k = 1; k <= 4; ++k) {
    const std::string k_unit = IndexUnit(k, unit);
    items += std::string(k > 1 ? ", " : "") + "O" + std::to_string(k) + " " + Figure(values[k - 1]) +
             (k_unit.empty() ? "" : " " + k_unit) + " (" + Escape(IndexMeaning(k)) + ")";
  }
  return items;
}

// The plan: its indices with the nominal robot (paper section 2) and the leg
// readings of every pose against the strokes (Fig. 8).
std::string PlanSection(const SessionPaths& paths, const Robot& nominal) {
  std::error_code error;
  if (!fs::exists(paths.plan, error)) return "";
  StatusOr<std::vector<Vector6d>> plan = LoadPoses(paths.plan);
  if (!plan.ok()) return "<h2>Plan</h2><p>" + Escape(plan.status().message()) + "</p>\n";
  std::vector<Pose> poses;
  for (const Vector6d& v : *plan) poses.push_back(nominal.PoseFromVector(v));
  const ObservabilityIndices o = ComputeIndices(nominal, poses);
  std::string html = "<h2>Plan</h2><p>" + std::to_string(poses.size()) +
                     " planned poses (plan.csv). Observability of the identification Jacobian with the nominal "
                     "robot (larger is better): " + IndexItems(o, LengthUnitName(nominal.length_unit)) +
                     ".</p>\n";
  // Fig. 8: planned poses crowd at the stroke ends.
  return html + ChartHtml(charts::LegReadingsChart(nominal, *plan));
}

// The implicit residual IK(pose) - reading of every leg at each calibration
// pose, with the nominal and the calibrated robot.
std::string ResidualSection(const SessionPaths& paths, const Robot& nominal) {
  const std::string used = ResultsFile(paths.dir, kUsedMeasurements);
  const std::string calibrated_path = ResultsFile(paths.dir, kCalibratedRobot);
  std::error_code error;
  if (!fs::exists(used, error) || !fs::exists(calibrated_path, error)) return "";
  StatusOr<std::vector<Measurement>> rows = LoadMeasurements(used);
  StatusOr<Robot> calibrated = LoadRobot(calibrated_path);
  if (!rows.ok() || !calibrated.ok())
    return "<h2>Residuals</h2><p>" + Escape(!rows.ok() ? rows.status().message() : calibrated.status().message()) +
           "</p>\n";
  return "<h2>Residuals</h2><p>The implicit residual (paper eq. 4, as a length) of every leg at each "
         "calibration pose, in the registered base frame.</p>\n" +
         ChartHtml(charts::CalibrationResidualsChart(nominal, *calibrated, *rows));
}

// The per-corner diagnostics of the calibration from pixels, when it wrote
// results/corner_residuals.csv (corner_report_section.h); the image frame is
// the session camera's.
std::string CornerSection(const std::string& dir, const SessionPaths& paths, const SessionConfig& config) {
  const std::string path = ResultsFile(paths.dir, kCornerResiduals);
  std::error_code error;
  if (!fs::exists(path, error)) return "";
  StatusOr<CornerResidualTable> table = LoadCornerResiduals(path);
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config.camera));
  if (!table.ok() || !camera.ok())
    return "<h2>Per-corner diagnostics</h2><p>" +
           Escape(!table.ok() ? table.status().message() : camera.status().message()) + "</p>\n";
  return CornerDiagnosticsSection(*table, camera->width, camera->height);
}

// Results computed from inputs that have changed since: say so at the top.
std::string StaleWarning(const SessionResults& results) {
  if (results.changed_inputs.empty()) return "";
  return "<p style=\"background:#fde8e8;border:1px solid #c00;padding:6px\"><b>Stale results.</b> " +
         Escape(ListNames(results.changed_inputs)) + " changed after these results were computed (" +
         Escape(results.manifest.created) + "): run <code>hexcal calibrate --session</code> again.</p>\n";
}

// The readings that failed the outlier screening (docs/calibration.md, "Outliers").
std::string OutlierSection(const CalibrationReport& report) {
  if (report.outliers.empty()) return "";
  std::string html = "<h2>Outliers</h2><p>Leg readings far beyond the noise model (|z| above " +
                     (report.screening ? Figure(report.screening->threshold) : std::string("the threshold")) +
                     "): residual = reading &minus; the length the " +
                     (report.instrument == Instrument::kPoints ? "tracker" : "camera") +
                     " pose implies.</p>\n<table><tr><th>" + MeasurementNoun(report.instrument) + "</th>"
                     "<th>legs.csv line</th><th>leg</th><th>residual (" +
                     Escape(report.length_unit) + ")</th><th>z (&sigma;)</th><th>in the fit</th></tr>\n";
  for (const OutlierReading& o : report.outliers) {
    html += "<tr><td>" + Escape(o.image) + "</td><td>" + (o.legs_line ? std::to_string(*o.legs_line) : "–") +
            "</td><td>" + std::to_string(o.leg) + "</td><td>" + Figure(o.residual) + "</td><td>" + Figure(o.z) +
            "</td><td>" + (o.excluded ? "excluded" : "kept") + "</td></tr>\n";
  }
  return html + "</table>\n";
}

// FK of the calibrated robot against the camera, per camera axis, and the
// finding (docs/calibration.md, "Bias along the optical axis").
std::string CameraFrameSection(const CalibrationReport& report) {
  if (!report.camera_frame_residuals) return "";
  const CameraFrameResiduals& r = *report.camera_frame_residuals;
  const std::string u = Escape(report.length_unit);
  std::string html =
      "<h2>Camera-frame residuals</h2><p>Where the calibrated robot puts the platform (FK from the readings) minus "
      "where the camera saw it, in the camera frame (z along the optical axis, away from the camera), over " +
      std::to_string(r.images) + " calibration images, platform depths " + Figure(r.depth_min) + " to " +
      Figure(r.depth_max) + " " + u + ". Slopes are unit-free: the residual's change per " + u +
      " of depth, and per " + u + " of the axis's own coordinate.</p>\n<table><tr><th>axis</th><th>mean (" + u +
      ")</th><th>std (" + u + ")</th><th>standard error (" + u +
      ")</th><th>t</th><th>slope with depth (%)</th><th>slope with the axis (%)</th></tr>\n";
  for (int a = 0; a < 3; ++a) {
    const AxisResiduals& axis = r.axes[a];
    html += "<tr><td>" + std::string(1, "xyz"[a]) + "</td><td>" + FixedLike(axis.mean, axis.standard_error) +
            "</td><td>" + Figure(axis.std_dev) + "</td><td>" + Figure(axis.standard_error) + "</td><td>" +
            FixedLike(axis.t, 1) + "</td><td>" + FixedLike(100 * axis.depth_slope, 100 * axis.depth_slope_se) +
            " &plusmn; " + FixedLike(100 * axis.depth_slope_se, 100 * axis.depth_slope_se, false) + "</td><td>" +
            FixedLike(100 * axis.scale_slope, 100 * axis.scale_slope_se) + " &plusmn; " +
            FixedLike(100 * axis.scale_slope_se, 100 * axis.scale_slope_se, false) + "</td></tr>\n";
  }
  std::string finding = CameraFrameFindingText(r);
  if (!finding.empty()) finding[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(finding[0])));
  return html + "</table><p><b>" + Escape(finding) + ".</b></p>\n";
}

}  // namespace

StatusOr<std::string> SessionReportHtml(const std::string& dir) {
  const SessionPaths paths(dir);
  StatusOr<SessionResults> loaded = LoadSessionResults(dir);
  if (!loaded.ok()) return loaded.status().WithHint(" (run hexcal calibrate --session first)");
  const CalibrationReport& report = loaded->report;
  const std::string unit = report.length_unit;
  std::string html =
      "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>hexcal session report</title><style>"
      "body{font-family:sans-serif;max-width:900px;margin:2em auto}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}svg{max-width:100%;height:auto}"
      ".verdict{border:3px solid;border-radius:6px;padding:0 1em 1em;margin-bottom:1.5em}"
      ".verdict h2{margin:0.5em 0}.verdict td,.verdict th{text-align:left;vertical-align:top;font-size:90%}"
      "</style></head><body>\n";
  // The title, a stale warning if any, then the verdict: what the reader
  // needs before any figure.
  html += "<h1>Session " + Escape(dir) + "</h1>\n";
  html += StaleWarning(*loaded);
  html += VerdictBox(MakeVerdict(report));
  const bool points = report.instrument == Instrument::kPoints;
  html += "<p>" + std::to_string(report.images) + (points ? " poses measured by points: " : " images: ") +
          std::to_string(report.calibration_images) + " for calibration, " +
          std::to_string(report.held_out_images) + " held out, " + std::to_string(report.unusable_images) +
          (points ? " whose points do not fit.</p>\n" : " without a usable target pose.</p>\n");
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<Robot> nominal = LoadSessionRobot(dir, *config);
  if (!nominal.ok()) return nominal.status();
  html += PlanSection(paths, *nominal);
  const RegistrationSummary& reg = report.registration;
  html += "<h2>Registration</h2><p>Closure |A&middot;Y &minus; X&middot;B| with the nominal robot: RMS " +
          Figure(reg.position_rms) + " " + Escape(unit) + ", " + Figure(reg.angle_rms_deg) +
          "&deg;; with the calibrated robot: " + Figure(report.closure_position_rms) + " " + Escape(unit) + ", " +
          Figure(report.closure_angle_rms_deg) + "&deg;.</p>\n";
  html += CalibrationMethodSection(report);
  html += CornerSection(dir, paths, *config);

  const std::vector<double> rms = MeasurementRms(paths.camera_poses);
  if (!rms.empty()) html += "<h2>Measurements</h2>\n" + ChartHtml(charts::MeasurementRmsChart(rms));

  if (report.validation) {
    const ValidationSummary& v = *report.validation;
    const charts::ValidationErrors errors{v.before.position_rms, v.after.position_rms, v.before.orientation_rms,
                                          v.after.orientation_rms};
    html += "<h2>Validation</h2>\n" + ChartHtml(charts::ValidationSummaryChart(errors, unit));
  }
  html += StudyReportSection(dir);  // the section 8 study, when study/ holds one

  html += CameraFrameSection(report);
  html += OutlierSection(report);
  html += ResidualSection(paths, *nominal);
  std::vector<charts::ParameterChange> changes;
  for (const ParameterEstimate& p : report.parameters)
    changes.push_back({p.leg, p.name, p.estimate - p.nominal, p.sigma.value_or(0)});
  html += "<h2>Calibrated parameters</h2>\n" + ChartHtml(charts::ParameterChangeChart(changes, unit)) +
          ParameterTable(report.parameters, unit);
  return html + "</body></html>\n";
}

StatusOr<std::string> WriteSessionReport(const ReportRequest& request) {
  const std::string out =
      request.out.empty() ? ResultsFile(request.session, kHtmlReport) : request.out;
  std::error_code exists_error;
  if (!request.out.empty() && !request.force && fs::exists(out, exists_error))
    return Status::BadInput(out + ": exists; use --force to overwrite it");
  // Writing into results/: held while reading it and writing, or a run
  // publishing a new results/ meanwhile would be described by the old page.
  // A page written elsewhere only reads (LoadSessionResults checks the unit).
  std::optional<SessionLock> lock;
  if (request.out.empty()) {
    StatusOr<SessionLock> acquired = SessionLock::Acquire(request.session, LockWait::kBriefly);
    if (!acquired.ok()) return acquired.status();
    lock.emplace(std::move(*acquired));
  }
  StatusOr<std::string> html = SessionReportHtml(request.session);
  if (!html.ok()) return html.status();
  if (Status s = WriteFileAtomically(out, *html); !s.ok()) return s;
  return out;
}

}  // namespace hexcal::workflow

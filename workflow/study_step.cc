#include "workflow/study_step.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "charts/chart_render.h"
#include "charts/figures.h"
#include "core/parallel.h"
#include "workflow/json_forms.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

constexpr SubsetMetric kMetrics[] = {SubsetMetric::kO1,
                                     SubsetMetric::kO2,
                                     SubsetMetric::kO3,
                                     SubsetMetric::kO4,
                                     SubsetMetric::kHeldOutPosition,
                                     SubsetMetric::kHeldOutOrientation};

// The figure of each metric in `--plots`: Fig. 18 per index, Fig. 19 per error.
const char* FigureStem(SubsetMetric metric) {
  switch (metric) {
    case SubsetMetric::kO1:
      return "fig18_o1";
    case SubsetMetric::kO2:
      return "fig18_o2";
    case SubsetMetric::kO3:
      return "fig18_o3";
    case SubsetMetric::kO4:
      return "fig18_o4";
    case SubsetMetric::kHeldOutPosition:
      return "fig19_position";
    case SubsetMetric::kHeldOutOrientation:
      return "fig19_orientation";
  }
  return "";
}

// What a person reads for the metric, with its unit.
std::string MetricLabel(SubsetMetric metric, const std::string& unit) {
  switch (metric) {
    case SubsetMetric::kHeldOutPosition:
      return "held-out position RMS (" + unit + ")";
    case SubsetMetric::kHeldOutOrientation:
      return "held-out orientation RMS (deg)";
    default:
      return SubsetMetricName(metric);
  }
}

bool IsError(SubsetMetric metric) { return !HigherIsBetter(metric); }

// The selected subset's value; NaN for an error when its calibration failed.
double SelectedValue(const SubsetStudyResult& result, SubsetMetric metric) {
  if (IsError(metric) && !result.selected.ok) return std::nan("");
  return MetricValue(result.selected, metric);
}

std::vector<StudyMetric> SummarizeMetrics(const SubsetStudyResult& result) {
  std::vector<StudyMetric> metrics;
  for (SubsetMetric metric : kMetrics) {
    const std::vector<double> values = RandomValues(result, metric);
    const double selected = SelectedValue(result, metric);
    const double percentile = std::isfinite(selected) ? PercentBeaten(values, selected, HigherIsBetter(metric)) : 0;
    metrics.push_back({metric, selected, SummarizeDistribution(values), percentile});
  }
  return metrics;
}

Status CheckFiguresFree(const StudyRequest& request) {
  if (request.plots.empty()) return Status::Ok();
  std::vector<std::string> stems;
  for (SubsetMetric metric : kMetrics) stems.push_back(FigureStem(metric));
  return charts::CheckChartFilesFree(request.plots, stems, request.force);
}

// --plots DIR: one histogram per metric (charts/figures.h), DIR created if missing.
Status WriteFigures(StudyOutcome* outcome) {
  const std::string& directory = outcome->request.plots;
  if (Status s = charts::CreatePlotsFolder(directory); !s.ok()) return s;
  const SubsetStudyResult& result = outcome->result;
  const std::string subsets =
      std::to_string(result.random.size()) + " random " + std::to_string(outcome->request.study.select) + "-subsets";
  for (SubsetMetric metric : kMetrics) {
    const bool index = !IsError(metric);
    const std::string title =
        std::string(index ? "Fig. 18: " : "Fig. 19: ") + MetricLabel(metric, outcome->length_unit) + ", " + subsets;
    const charts::ChartSpec spec = charts::SubsetHistogramChart(
        title, MetricLabel(metric, outcome->length_unit), RandomValues(result, metric), SelectedValue(result, metric));
    if (Status s = charts::WriteChartFiles(spec, directory, FigureStem(metric), &outcome->figures); !s.ok()) return s;
  }
  return Status::Ok();
}

// As printf's %.4g.
std::string FormatFigure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json DistributionJson(const Distribution& d) {
  return {{"count", d.count}, {"min", d.min}, {"p5", d.p5},   {"p25", d.p25},   {"median", d.median},
          {"p75", d.p75},     {"p95", d.p95}, {"max", d.max}, {"mean", d.mean}, {"std", d.std}};
}

nlohmann::json SelectedJson(const StudyOutcome& outcome) {
  const SubsetOutcome& selected = outcome.result.selected;
  nlohmann::json images = nlohmann::json::array();
  for (int j : selected.poses) images.push_back(outcome.images[j]);
  nlohmann::json percentiles;
  for (const StudyMetric& m : outcome.metrics) {
    percentiles[SubsetMetricName(m.metric)] = std::isfinite(m.selected) ? nlohmann::json(m.percentile) : nullptr;
  }
  return {{"poses", selected.poses},
          {"images", images},
          {"iterations", outcome.result.selection_iterations},
          {"ok", selected.ok},
          {"failure", selected.ok ? nlohmann::json(nullptr) : nlohmann::json(selected.failure)},
          {"indices", IndicesJson(selected.indices)},
          {"heldout_position_rms", NumberOrNull(SelectedValue(outcome.result, SubsetMetric::kHeldOutPosition))},
          {"heldout_orientation_rms", NumberOrNull(SelectedValue(outcome.result, SubsetMetric::kHeldOutOrientation))},
          {"heldout_fk_failed", selected.heldout_fk_failed},
          {"percentile", percentiles[SubsetMetricName(SubsetMetric::kHeldOutPosition)]},
          {"percentiles", percentiles}};
}

nlohmann::json RandomJson(const StudyOutcome& outcome) {
  const SubsetStudyResult& result = outcome.result;
  nlohmann::json random = {{"count", result.random.size()},
                           {"failed", result.failed},
                           {"first_failure", result.failed > 0 ? nlohmann::json(result.first_failure) : nullptr}};
  for (const StudyMetric& m : outcome.metrics) random[SubsetMetricName(m.metric)] = DistributionJson(m.random);
  return random;
}

// The label, the selected value, the distribution's columns and the rank, one
// line; "-" for the selected value and rank when its calibration failed.
void PrintMetricRow(const StudyMetric& m, const std::string& unit, std::ostream& out) {
  char line[320];
  const Distribution& d = m.random;
  const bool known = std::isfinite(m.selected);
  std::snprintf(line, sizeof line, "%-31s %10s %10.4g %10.4g %10.4g %10.4g %10.4g %10.4g %10.4g",
                MetricLabel(m.metric, unit).c_str(), known ? FormatFigure(m.selected).c_str() : "-", d.min, d.p5,
                d.median, d.mean, d.std, d.p95, d.max);
  out << line;
  if (known) {
    std::snprintf(line, sizeof line, " %10.4g %%", m.percentile);
    out << line;
  } else {
    out << "          -";
  }
  out << "\n";
}

}  // namespace

StatusOr<StudyOutcome> RunStudy(StudyRequest request, const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  if (!request.study.IsValid(&error)) return Status::Error(error);
  if (Status s = CheckFiguresFree(request); !s.ok()) return s;
  StatusOr<MeasuredSession> session = LoadMeasuredSession(request.session, request.wait, hooks);
  if (!session.ok()) return session.status();
  // calibrate --session's fit, without the outlier screening: each subset is
  // the paper's plain least squares, and 13 rows leave little to screen with.
  request.study.calibration = SessionCalibrationOptions(session->noise, OutlierScreening{});
  if (request.weighted_selection) request.study.selection_noise = session->noise;

  const auto subsets_start = std::chrono::steady_clock::now();
  StatusOr<SubsetStudyResult> result = RunSubsetStudy(session->nominal, session->measurements, request.study, hooks);
  if (!result.ok()) return result.status();  // bad options are bad input, a failed study a failure
  StudyOutcome outcome;
  outcome.subsets_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - subsets_start).count();
  outcome.request = request;
  outcome.robot = session->nominal.name;
  outcome.length_unit = LengthUnitName(session->nominal.length_unit);
  outcome.images = session->images;
  outcome.unusable = session->unusable;
  outcome.result = std::move(*result);
  outcome.metrics = SummarizeMetrics(outcome.result);
  outcome.threads = ParallelWorkers(request.study.subsets + 1, request.study.num_threads);
  if (!request.plots.empty()) {
    if (Status s = WriteFigures(&outcome); !s.ok()) return s.AsFailure();
  }
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

nlohmann::json ToJson(const StudyOutcome& outcome) {
  const SubsetStudyOptions& study = outcome.request.study;
  return {{"session", outcome.request.session},
          {"robot", outcome.robot},
          {"length_unit", outcome.length_unit},
          {"measured", outcome.result.measurements},
          {"unusable", outcome.unusable},
          {"select", study.select},
          {"subsets", study.subsets},
          {"criterion", CriterionName(study.criterion)},
          {"secondary", study.secondary ? nlohmann::json(CriterionName(*study.secondary)) : nullptr},
          {"starts", study.selection_starts},
          {"weighted_selection", outcome.request.weighted_selection},
          {"seed", study.seed},
          {"selected", SelectedJson(outcome)},
          {"random", RandomJson(outcome)},
          {"figures", outcome.figures},
          {"threads", outcome.threads},
          {"subsets_seconds", outcome.subsets_seconds},
          {"seconds", outcome.seconds}};
}

std::string FormatStudySummary(const StudyOutcome& outcome) {
  const SubsetStudyOptions& study = outcome.request.study;
  const SubsetStudyResult& result = outcome.result;
  const int held_out = result.measurements - study.select;
  std::ostringstream out;
  out << "section 8 study of session " << outcome.request.session << " (robot " << outcome.robot
      << "): " << result.measurements << " measured poses"
      << (outcome.unusable > 0
              ? ", " + std::to_string(outcome.unusable) + " images without a usable board pose left out"
              : "")
      << "\n"
      << "selected: IOOPS on " << CriterionName(study.criterion)
      << (study.secondary ? std::string(", secondary ") + CriterionName(*study.secondary) : "")
      << (outcome.request.weighted_selection ? " (rows weighted by the session's noise model)" : "") << ", "
      << study.select << " of the measured poses in " << result.selection_iterations << " iterations:";
  for (int j : result.selected.poses) out << " " << outcome.images[j];
  out << "\nrandom: " << result.random.size() << " subsets of " << study.select << ", seed " << study.seed
      << "; each calibrated from the nominal robot and validated by FK on the " << held_out
      << " poses it leaves out\n\n";
  char header[320];
  std::snprintf(header, sizeof header, "%-31s %10s %10s %10s %10s %10s %10s %10s %10s %10s\n", "", "selected", "min",
                "p5", "median", "mean", "std", "p95", "max", "beats");
  out << header;
  for (const StudyMetric& m : outcome.metrics) PrintMetricRow(m, outcome.length_unit, out);
  out << "\n";
  if (result.selected.ok) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "the selected subset validates better than %.1f %% of the random subsets on the held-out position "
                  "RMS, %.1f %% on the orientation RMS\n",
                  outcome.metrics[4].percentile, outcome.metrics[5].percentile);
    out << line;
  } else {
    out << "warning: the selected subset could not be calibrated: " << result.selected.failure << "\n";
  }
  if (result.failed > 0) {
    out << "warning: " << result.failed << " of " << result.random.size()
        << " random subsets could not be calibrated or validated and are not in the error statistics; first: "
        << result.first_failure << "\n";
  }
  for (const std::string& figure : outcome.figures) out << "figure written to " << figure << "\n";
  char timing[200];
  std::snprintf(timing, sizeof timing,
                "selection and %d calibrations and validations in %.2f s on %d %s; done in %.2f s\n", study.subsets + 1,
                outcome.subsets_seconds, outcome.threads, outcome.threads == 1 ? "thread" : "threads", outcome.seconds);
  out << timing;
  return out.str();
}

}  // namespace hexcal::workflow

#include "session/study_outcome.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "charts/chart_render.h"
#include "charts/figures.h"

namespace hexcal::workflow {
namespace {

bool IsError(SubsetMetric metric) { return !HigherIsBetter(metric); }

// The selected subset's value; NaN for an error when its calibration failed.
double SelectedValue(const SubsetStudyResult& result, SubsetMetric metric) {
  if (IsError(metric) && !result.selected.ok) return std::nan("");
  return MetricValue(result.selected, metric);
}

// As printf's %.4g.
std::string FormatFigure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// The label, the selected value, the distribution's columns and the rank, one
// line; "-" for the selected value and rank when its calibration failed.
void PrintMetricRow(const StudyMetric& m, const std::string& unit, std::ostream& out) {
  char line[320];
  const Distribution& d = m.random;
  const bool known = std::isfinite(m.selected);
  std::snprintf(line, sizeof line, "%-31s %10s %10.4g %10.4g %10.4g %10.4g %10.4g %10.4g %10.4g",
                SubsetMetricLabel(m.metric, unit).c_str(), known ? FormatFigure(m.selected).c_str() : "-", d.min, d.p5,
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

std::vector<StudyMetric> SummarizeMetrics(const SubsetStudyResult& result) {
  std::vector<StudyMetric> metrics;
  for (SubsetMetric metric : kSubsetMetrics) {
    const std::vector<double> values = RandomValues(result, metric);
    const double selected = SelectedValue(result, metric);
    const double percentile = std::isfinite(selected) ? PercentBeaten(values, selected, HigherIsBetter(metric)) : 0;
    metrics.push_back({metric, selected, SummarizeDistribution(values), percentile});
  }
  return metrics;
}

StudyRecord MakeStudyRecord(const StudyOutcome& outcome) {
  const SubsetStudyOptions& study = outcome.request.study;
  const SubsetStudyResult& result = outcome.result;
  StudyRecord r;
  r.created = outcome.created;
  r.session = outcome.request.session;
  r.robot = outcome.robot;
  r.length_unit = outcome.length_unit;
  r.measured = result.measurements;
  r.unusable = outcome.unusable;
  r.select = study.select;
  r.subsets = study.subsets;
  r.starts = study.selection_starts;
  r.criterion = study.criterion;
  r.secondary = study.secondary;
  r.weighted_selection = outcome.request.weighted_selection;
  r.seed = study.seed;
  r.selected = {result.selected.poses,
                {},
                result.selection_iterations,
                result.selected.ok,
                result.selected.failure,
                result.selected.indices,
                result.selected.heldout_fk_failed};
  for (int j : result.selected.poses) r.selected.images.push_back(outcome.images[j]);
  r.random_count = static_cast<int>(result.random.size());
  r.random_failed = result.failed;
  r.first_failure = result.first_failure;
  r.metrics = outcome.metrics;
  r.figures = outcome.figures;
  r.threads = outcome.threads;
  r.subsets_seconds = outcome.subsets_seconds;
  r.seconds = outcome.seconds;
  r.inputs = outcome.inputs;
  r.saved = outcome.saved;
  return r;
}

nlohmann::json ToJson(const StudyOutcome& outcome) { return ToJson(MakeStudyRecord(outcome)); }

const char* StudyFigureStem(SubsetMetric metric) {
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

Status WriteStudyFigures(const StudyOutcome& outcome, const std::string& directory, std::vector<std::string>* written) {
  const SubsetStudyResult& result = outcome.result;
  for (SubsetMetric metric : kSubsetMetrics) {
    const charts::ChartSpec spec =
        charts::StudyMetricChart(metric, RandomValues(result, metric), SelectedValue(result, metric),
                                 outcome.request.study.select, outcome.length_unit);
    if (Status s = charts::WriteChartFiles(spec, directory, StudyFigureStem(metric), written); !s.ok()) return s;
  }
  return Status::Ok();
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
  out << "(O1..O4: the subset's observability indices, larger is better: O1 the volume of the parameters' "
         "uncertainty, O2 sigma_min / sigma_max, O3 sigma_min, O4 sigma_min^2 / sigma_max; hexcal indices)\n\n";
  out << StudyRankSentence(MakeStudyRecord(outcome)) << "\n";
  if (result.failed > 0) {
    out << "warning: " << result.failed << " of " << result.random.size()
        << " random subsets could not be calibrated or validated and are not in the error statistics; first: "
        << result.first_failure << "\n";
  }
  for (const std::string& figure : outcome.figures) out << "figure written to " << figure << "\n";
  if (!outcome.saved.empty()) out << "study kept in " << outcome.saved << " (hexcal report shows it)\n";
  char timing[200];
  std::snprintf(timing, sizeof timing,
                "selection and %d calibrations and validations in %.2f s on %d %s; done in %.2f s\n", study.subsets + 1,
                outcome.subsets_seconds, outcome.threads, outcome.threads == 1 ? "thread" : "threads", outcome.seconds);
  out << timing;
  return out.str();
}

}  // namespace hexcal::workflow

#include "report/study_report_section.h"

#include <cctype>
#include <cmath>
#include <sstream>

#include "charts/chart_render.h"
#include "charts/figures.h"
#include "report/html_text.h"
#include "session/session_study.h"

namespace hexcal::workflow {
namespace {

// Table 5 and Fig. 19 first: the held-out errors are what the study is for.
constexpr SubsetMetric kReportOrder[] = {SubsetMetric::kHeldOutPosition,
                                         SubsetMetric::kHeldOutOrientation,
                                         SubsetMetric::kO1,
                                         SubsetMetric::kO2,
                                         SubsetMetric::kO3,
                                         SubsetMetric::kO4};

std::string Escape(const std::string& text) { return HtmlEscape(text); }

// 4 significant digits, as the report's other tables; "–" for no value.
std::string Figure(double value) {
  if (!std::isfinite(value)) return "–";
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

std::string ChartHtml(const charts::ChartSpec& spec) {
  StatusOr<std::string> svg = charts::ChartSvgElement(spec);
  return svg.ok() ? *svg + "\n" : "<p>Chart not drawn: " + Escape(svg.status().message()) + "</p>\n";
}

// The study describes inputs that have changed since: say so first, in red.
std::string StaleLine(const SessionStudy& study) {
  if (!study.Stale()) return "";
  return "<p style=\"background:#fde8e8;border:1px solid #c00;color:#c00;padding:6px\"><b>Stale study.</b> " +
         Escape(ListNames(study.changed_inputs)) + " changed after this study was made (" +
         Escape(study.record.created) + "): run <code>hexcal study --session</code> again.</p>\n";
}

std::string Description(const StudyRecord& r) {
  const int held_out = r.measured - r.select;
  std::string criterion = CriterionName(r.criterion);
  if (r.secondary) criterion += std::string(", secondary ") + CriterionName(*r.secondary);
  return "<p>The paper's section 8 on this session's measured poses (<code>hexcal study</code>, " + Escape(r.created) +
         "): IOOPS on " + criterion +
         (r.weighted_selection ? " (rows weighted by the noise model)" : " (unweighted J<sub>P</sub>)") + " selected " +
         std::to_string(r.select) + " of the " + std::to_string(r.measured) + " measured poses; that subset and " +
         std::to_string(r.random_count) + " random " + std::to_string(r.select) + "-subsets (seed " +
         std::to_string(r.seed) +
         ") were each calibrated from the nominal robot and validated by forward kinematics on the " +
         std::to_string(held_out) + " poses they leave out.</p>\n";
}

// Table 5's form: the selected subset against the random subsets' distribution.
std::string Table5(const StudyRecord& r) {
  std::string html =
      "<table><tr><th style=\"text-align:left\">quantity</th><th>selected</th><th>random mean</th><th>random "
      "std</th><th>random median</th>"
      "<th>random p5 – p95</th><th>selected beats</th></tr>\n";
  for (SubsetMetric metric : kReportOrder) {
    const StudyMetric& m = r.Metric(metric);
    const std::string beats = std::isfinite(m.selected) ? Figure(m.percentile) + " %" : "–";
    html += "<tr><td style=\"text-align:left\">" + Escape(SubsetMetricLabel(metric, r.length_unit)) + "</td><td><b>" +
            Figure(m.selected) + "</b></td><td>" + Figure(m.random.mean) + "</td><td>" + Figure(m.random.std) +
            "</td><td>" + Figure(m.random.median) + "</td><td style=\"white-space:nowrap\">" + Figure(m.random.p5) +
            " – " + Figure(m.random.p95) + "</td><td>" + beats + "</td></tr>\n";
  }
  return html +
         "</table>\n<p>Held-out errors: lower is better; indices: higher is better. \"Beats\": the "
         "percentage of random subsets the selected one does better than (ties count half).</p>\n";
}

std::string Figures(const SessionStudy& study) {
  const StudyRecord& r = study.record;
  // Two a row: the pairs belong together (Fig. 19's two errors, Fig. 18's indices).
  std::string html;
  const std::string cell = "<div style=\"flex:1;min-width:0\">";
  int shown = 0;
  for (SubsetMetric metric : kReportOrder) {
    html += (shown++ % 2 == 0 ? "<div style=\"display:flex;gap:8px\">" : "") + cell;
    html += ChartHtml(charts::StudyMetricChart(metric, study.RandomValuesOf(metric), r.Metric(metric).selected,
                                               r.select, r.length_unit));
    html += shown % 2 == 0 ? "</div></div>\n" : "</div>";
  }
  return html;
}

}  // namespace

std::string StudyReportSection(const std::string& dir) {
  if (!HasSessionStudy(dir)) return "";
  StatusOr<SessionStudy> study = LoadSessionStudy(dir);
  if (!study.ok()) return "<h2 id=\"study\">Section 8 study</h2><p>" + Escape(study.status().message()) + "</p>\n";
  const StudyRecord& r = study->record;
  std::string html = "<h2 id=\"study\">Section 8 study</h2>\n" + StaleLine(*study) + Description(r);
  std::string rank = StudyRankSentence(r);
  rank[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(rank[0])));
  html += "<p><b>" + Escape(rank) + ".</b></p>\n";
  if (r.random_failed > 0)
    html += "<p>" + std::to_string(r.random_failed) + " of " + std::to_string(r.random_count) +
            " random subsets could not be calibrated or validated and are not in the error statistics; first: " +
            Escape(r.first_failure) + "</p>\n";
  html += Table5(r);
  std::string images;
  for (const std::string& image : r.selected.images) images += (images.empty() ? "" : ", ") + image;
  html += "<p>Selected images: " + Escape(images) + ".</p>\n";
  return html + Figures(*study);
}

}  // namespace hexcal::workflow

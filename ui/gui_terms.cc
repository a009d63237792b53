#include "ui/gui_terms.h"

#include <QRegularExpression>
#include <utility>
#include <vector>

namespace hexcal::ui {
namespace {

// The CLI's phrases the workflow's messages hold, most specific first.
const std::vector<std::pair<QRegularExpression, QString>>& Phrases() {
  static const std::vector<std::pair<QRegularExpression, QString>> phrases = [] {
    const std::vector<std::pair<const char*, const char*>> table = {
        {R"(use it with --controller sim|it needs --controller sim)",
         "choose 'sim' in the Acquire step's Controller list too"},
        {R"(no plan in the session; run hexcal plan --out \S+ or pass --poses FILE)",
         "no plan in the session: run the planner (Plan step) first"},
        {R"(no plan\.csv: hexcal plan --out \S+)", "no plan.csv: run the planner (Plan step)"},
        {R"(acquire the planned poses \(hexcal acquire\))", "acquire the planned poses (Acquire step)"},
        {R"(\(hexcal acquire resumes\))", "(Run the rest in the Acquire step resumes)"},
        {R"(then run hexcal acquire again to go on)", "then press Run the rest again to go on"},
        {R"(hexcal acquire did not write it: move it away, or record its readings \(hexcal session record\), then run again)",
         "the Acquire step did not write it: move it away, or type its readings in the Measure step's table, then "
         "capture again"},
        {R"(the GUI's readings table, `hexcal session record`, or a CSV image,L1\.\.L6 imported)",
         "the Measure step's readings table, or Import leg readings…"},
        {R"(\(calibrate --session measures them\))", "(Calibrate measures them)"},
        {R"(no results: hexcal calibrate --session \S+)", "no results: run the Calibrate step"},
        {R"(run <code>hexcal calibrate --session[^<]*</code> (again|first))", "run the Calibrate step \\1"},
        {R"(`hexcal calibrate --session[^`]*`)", "the Calibrate step"},
        {R"(run hexcal calibrate --session (again|first))", "run the Calibrate step \\1"},
        {R"(hexcal calibrate --session)", "the Calibrate step"},
        {R"(\(hexcal intrinsics\))", "(Measure step: Intrinsics from folder…)"},
        {R"(\(hexcal plan picks them\))", "(the Plan step picks them)"},
        {R"(with hexcal plan \(IOOPS\))", "with the planner (Plan step, IOOPS)"},
        {R"(\(hexcal plan\))", "(Plan step)"},
        {R"(with hexcal measure --session)", "in the Measure step's image list"},
        {R"(\(`hexcal detect --images IMAGES --target TARGET` lists each image's tags\))",
         "(the Measure step shows each image's tags)"},
        {R"(without --keep-outliers it is left out)", "it is left out of the fit"},
        {R"( \(--keep-outliers keeps it\))", ""},
        {R"(--noise-\* match)", "the session's noise model (session.yaml) matches"},
        {R"(run hexcal study again)", "run the study again (Validate step, study tab)"},
        {R"( \(hexcal report shows it\))", ""},
    };
    std::vector<std::pair<QRegularExpression, QString>> made;
    for (const auto& [pattern, replacement] : table) made.emplace_back(QRegularExpression(pattern), replacement);
    return made;
  }();
  return phrases;
}

}  // namespace

QString InGuiTerms(const QString& text) {
  QString said = text;
  for (const auto& [phrase, replacement] : Phrases()) said.replace(phrase, replacement);
  return said;
}

}  // namespace hexcal::ui

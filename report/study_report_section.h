// The "Section 8 study" section of the HTML report (session_report.h), from
// the study the session keeps in study/ (session_study.h): where IOOPS's
// subset ranks among the random ones, the Table 5 figures (the selected
// subset against the random subsets' mean, spread and median of the held-out
// position and orientation RMS, and of O1..O4), Figs. 19 and 18 as inline
// SVG, and a red "stale" line when the session's inputs changed since the
// study. Its own file so that the report's other sections change apart.
// Draws with Qt: call on the thread that owns the QApplication.
//
//   html += StudyReportSection("run1");  // "" when run1 has no study/
#pragma once

#include <string>

namespace hexcal::workflow {

// "" when the session has no study; a study that does not load is a
// section with its error, not a failed report.
std::string StudyReportSection(const std::string& session_dir);

}  // namespace hexcal::workflow

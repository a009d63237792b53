// The HTML report of a calibrated session (docs/session.md): one
// self-contained page with the plan (indices, leg lengths as in Fig. 8 of the
// paper), measurement quality per image, the registration, the calibration
// residuals before and after, the calibrated parameters with σ and their
// change from nominal, the held-out validation before and after, and the
// camera-frame residuals with their bias finding (camera_frame_diagnosis.h),
// and the section 8 study when the session keeps one (study_report_section.h). Charts
// are inline SVG of the figures in charts/figures.h (chart_render.h); nothing
// is fetched. Draws with Qt: call on the thread that owns the QApplication.
//
//   StatusOr<std::string> html = SessionReportHtml("run1");
//   if (html.ok()) WriteFileAtomically("run1/results/report.html", *html);
#pragma once

#include <string>

#include "core/status.h"

namespace hexcal::workflow {

// Needs DIR/results/report.json (hexcal calibrate --session); the plan and
// residual sections appear when plan.csv and the calibration files exist.
StatusOr<std::string> SessionReportHtml(const std::string& dir);

struct ReportRequest {
  std::string session;
  std::string out;     // the HTML file to write; empty: DIR/results/report.html
  bool force = false;  // replace an existing `out` (DIR/results/report.html is always replaced)
};

// Writes the page; returns the path written.
StatusOr<std::string> WriteSessionReport(const ReportRequest& request);

}  // namespace hexcal::workflow

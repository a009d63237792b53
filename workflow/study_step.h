// The section 8 study on a recorded session (`hexcal study`;
// docs/calibration.md, "The section 8 study"): the session's measured poses
// (LoadMeasuredSession, session_calibrate.h), IOOPS's subset of N of them
// against K random N-subsets, each calibrated as calibrate --session does
// and validated by FK on the poses it leaves out (core/subset_study.h);
// the distributions of O1..O4 (Fig. 18) and of the held-out position and
// orientation RMS (Fig. 19, Table 5), and where the selected subset ranks.
// The result is kept in the session's study/ folder (session_study.h).
//
//   StudyRequest request;
//   request.session = "run1";
//   request.study.select = 13;
//   StatusOr<StudyOutcome> study = RunStudy(request, hooks);  // also writes run1/study/
//   if (study.ok()) std::cout << FormatStudySummary(*study);
#pragma once

#include "core/job_hooks.h"
#include "session/study_outcome.h"

namespace hexcal::workflow {

// Stages through hooks: those of the measure step when images are new, then
// "select (IOOPS)" and "calibrate and validate subsets" (progress: subsets).
StatusOr<StudyOutcome> RunStudy(StudyRequest request, const JobHooks& hooks = {});

}  // namespace hexcal::workflow

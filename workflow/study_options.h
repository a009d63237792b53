// The options of the section 8 study a user tunes (`hexcal study`;
// docs/calibration.md, "The section 8 study"): N, K, IOOPS's criteria and
// starts, the weighting of its rows, the seed and the threads — each
// described once in StudyOptions() (core/option_spec.h). That table makes
// the `hexcal study` flags, the GUI's study form (ui/study_view.h) and the
// table in docs/cli.md.
//
//   StudyRequest request;  // the defaults: N = 13, K = 6000, O1, weighted rows
//   Status s = ApplyOptionEntries(StudyOptions(), {{"select", "13"}, {"criterion", "O4"}}, &request, "study");
#pragma once

#include "core/option_spec.h"
#include "workflow/study_step.h"

namespace hexcal::workflow {

// The session, the figures folder, --force, --wait and --no-save are not in
// it: they say where and how to run, not what the study is.
const OptionTable<StudyRequest>& StudyOptions();

}  // namespace hexcal::workflow

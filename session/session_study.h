// The section 8 study kept in the session (docs/session.md, "Layout",
// `study/`): `hexcal study` and the GUI's study view publish their result
// whole into DIR/study under the session lock (core/staged_folder.h), as
// `calibrate --session` publishes results/:
//
//   study.json   the study's record (study_record.h; what `--json` prints),
//                with the SHA-256 of the session inputs it read
//   subsets.csv  every subset's poses, indices and held-out errors: the data
//                behind Figs. 18 and 19 (row 0 the selected subset)
//   fig18_o1 … fig18_o4, fig19_position, fig19_orientation (.svg, .png)
//
// One reader, LoadSessionStudy, serves the HTML report and the GUI; it
// compares the inputs with the session as it is now, so a study of readings
// or images changed since is marked stale.
//
//   if (HasSessionStudy("run1")) {
//     StatusOr<SessionStudy> study = LoadSessionStudy("run1");
//     if (study.ok() && study->Stale()) ...  // legs.csv changed since: name study->changed_inputs
//   }
#pragma once

#include <string>
#include <vector>

#include "core/session_lock.h"
#include "session/study_outcome.h"
#include "session/study_record.h"

namespace hexcal::workflow {

std::string StudyFolderPath(const std::string& session_dir);  // DIR/study
bool HasSessionStudy(const std::string& session_dir);         // DIR/study/study.json exists

// Publishes DIR/study whole (the files above) under the session lock and
// sets outcome->saved. Draws the figures with Qt: call on the thread that
// owns the QApplication (in the CLI, RunStudy does; the GUI, on its thread).
Status SaveSessionStudy(StudyOutcome* outcome, LockWait wait);

struct SessionStudy {
  StudyRecord record;
  // Each metric's values over the random subsets, in record.metrics order:
  // the indices of every one, the held-out errors of those that were
  // calibrated and validated (RandomValues, core/subset_study.h).
  std::vector<std::vector<double>> random_values;
  // The session's inputs that changed since the study, by name (ListNames,
  // session_results.h); none: the study describes the session as it is.
  std::vector<std::string> changed_inputs;

  bool Stale() const { return !changed_inputs.empty(); }
  const std::vector<double>& RandomValuesOf(SubsetMetric metric) const;
};

// Reads DIR/study; `inputs`: the session's input hashes when the caller has
// them already (HashSessionInputs), else they are hashed here. A study.json
// or subsets.csv that is not hexcal's, or that do not match, is an error
// naming the file.
StatusOr<SessionStudy> LoadSessionStudy(const std::string& session_dir, const ContentHashes* inputs = nullptr);

}  // namespace hexcal::workflow

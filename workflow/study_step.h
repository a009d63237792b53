// The section 8 study on a recorded session (`hexcal study`;
// docs/calibration.md, "The section 8 study"): the session's measured poses
// (LoadMeasuredSession, session_calibrate.h), IOOPS's subset of N of them
// against K random N-subsets, each calibrated as calibrate --session does
// and validated by FK on the poses it leaves out (core/subset_study.h);
// the distributions of O1..O4 (Fig. 18) and of the held-out position and
// orientation RMS (Fig. 19, Table 5), and where the selected subset ranks.
//
//   StudyRequest request;
//   request.session = "run1";
//   request.study.select = 13;
//   StatusOr<StudyOutcome> study = RunStudy(request, hooks);
//   if (study.ok()) std::cout << FormatStudySummary(*study);
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/session_lock.h"
#include "core/subset_study.h"

namespace hexcal::workflow {

struct StudyRequest {
  std::string session;  // a session folder with images and readings
  // N, K, criteria, seed, threads. Its `calibration` is replaced by the
  // session's (SessionCalibrationOptions: weighted by each image's pose
  // covariance and the noise model) without the outlier screening.
  SubsetStudyOptions study;
  bool weighted_selection = true;  // IOOPS weighs its rows by the session's noise model (selection_noise)
  std::string plots;                // folder for the Fig. 18 and 19 histograms (SVG and PNG); may be empty
  bool force = false;               // replace figures already in `plots`
  LockWait wait = LockWait::kNo;    // for the session lock while images are measured
};

// One quantity of Figs. 18-19 / Table 5: the selected subset's value, its
// distribution over the random subsets, and the percentage of random subsets
// the selected one beats (higher indices, lower held-out errors; ties half).
struct StudyMetric {
  SubsetMetric metric;
  double selected = 0;
  Distribution random;
  double percentile = 0;
};

struct StudyOutcome {
  StudyRequest request;
  std::string robot, length_unit;
  std::vector<std::string> images;  // the image of each measured pose, the study's pose order
  int unusable = 0;                 // rows without a usable board pose, left out
  SubsetStudyResult result;
  std::vector<StudyMetric> metrics;  // O1..O4, held-out position and orientation RMS
  std::vector<std::string> figures;  // files written under `plots`
  double subsets_seconds = 0;        // the selection and the K + 1 calibrations and validations
  double seconds = 0;                // the whole study, measuring included
  int threads = 0;                   // the threads the subsets ran on
};

// Stages through hooks: those of the measure step when images are new, then
// "select (IOOPS)" and "calibrate and validate subsets" (progress: subsets).
StatusOr<StudyOutcome> RunStudy(StudyRequest request, const JobHooks& hooks = {});

// {"session", "robot", "length_unit", "measured", "unusable", "select", "subsets", "criterion", "secondary",
//  "seed", "selected": {"percentile", "percentiles", "indices", "heldout_position_rms", ...},
//  "random": {"count", "failed", "first_failure", "O1": {distribution}, ...}, "figures", "seconds", ...}
nlohmann::json ToJson(const StudyOutcome& outcome);
std::string FormatStudySummary(const StudyOutcome& outcome);

}  // namespace hexcal::workflow

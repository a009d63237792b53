// What the section 8 study asks and gives (split from study_step.h, whose
// RunStudy makes it): the request, the outcome, and its forms, a record
// (study_record.h), JSON, the printed summary and the Figs. 18 and 19 files.
// session_study.h keeps an outcome in the session's study/ folder, and
// RunStudy saves through it, so the forms sit below both (issue 37: the step
// and the session's study record included each other).
//
//   StatusOr<StudyOutcome> study = RunStudy(request, hooks);  // study_step.h
//   std::cout << FormatStudySummary(*study);
//   nlohmann::json json = ToJson(*study);
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/session_lock.h"
#include "core/subset_study.h"
#include "session/study_record.h"

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
  LockWait wait = LockWait::kNo;    // for the session lock while images are measured and study/ is written
  // Keep the result in the session's study/ folder (SaveSessionStudy,
  // session_study.h). It draws figures with Qt: a caller off the Qt thread
  // (the GUI's worker) sets false and saves on the GUI thread.
  bool save = true;
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
  ContentHashes inputs;              // the session's inputs as the study read them
  std::string created;               // UTC, when the study ended
  std::string saved;                 // the study folder written (session_study.h); empty: not kept
};

// Each metric's selected value, its distribution over the random subsets and
// the selected subset's rank.
std::vector<StudyMetric> SummarizeMetrics(const SubsetStudyResult& result);

// The outcome as its record (study_record.h), the form it is printed and kept in.
StudyRecord MakeStudyRecord(const StudyOutcome& outcome);
// ToJson(MakeStudyRecord(outcome)): {"format", "created", "session", "robot", "length_unit", "measured",
//  "unusable", "select", "subsets", "criterion", ..., "selected": {"percentile", "percentiles", "indices",
//  "heldout_position_rms", ...}, "random": {"count", "failed", "O1": {distribution}, ...}, "inputs", "saved", ...}
nlohmann::json ToJson(const StudyOutcome& outcome);
std::string FormatStudySummary(const StudyOutcome& outcome);

// The figure of each metric, as --plots and study/ hold it: "fig18_o1" ... "fig19_orientation".
const char* StudyFigureStem(SubsetMetric metric);
// Writes DIRECTORY/STEM.svg and .png for every metric (charts/figures.h,
// StudyMetricChart) and appends the paths to `written`. The folder must
// exist. Draws with Qt: on the thread that owns the QApplication.
Status WriteStudyFigures(const StudyOutcome& outcome, const std::string& directory, std::vector<std::string>* written);

}  // namespace hexcal::workflow

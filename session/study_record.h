// The section 8 study as one typed value: what `hexcal study --json` prints
// and what the session keeps in study/study.json (session_study.h). A run
// makes it (MakeStudyRecord, study_step.h); StudyRecordFromJson reads it back
// and names the key of a wrong file. The HTML report and the GUI read this,
// never the JSON by string keys. Keys: docs/cli.md, "study".
//
//   StudyRecord record = MakeStudyRecord(outcome);
//   const std::string text = ToJson(record).dump(2);
//   StatusOr<StudyRecord> back = StudyRecordFromJson(ToJson(record), "run1/study/study.json");
//   double beaten = back->Metric(SubsetMetric::kHeldOutPosition).percentile;
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/design_criteria.h"
#include "core/observability.h"
#include "core/subset_study.h"
#include "session/session_results.h"

namespace hexcal::workflow {

// One quantity of Figs. 18-19 / Table 5: the selected subset's value (NaN
// for an error when its calibration failed), its distribution over the
// random subsets, and the percentage of random subsets the selected one
// beats (higher indices, lower held-out errors; ties half).
struct StudyMetric {
  SubsetMetric metric;
  double selected = 0;
  Distribution random;
  double percentile = 0;
};

// IOOPS's subset of the measured poses.
struct StudySelection {
  std::vector<int> poses;           // 0-based indices of the measured poses (the usable rows, legs.csv order)
  std::vector<std::string> images;  // their images
  int iterations = 0;               // IOOPS's
  bool ok = false;                  // calibrated and validated
  std::string failure;              // why not
  ObservabilityIndices indices;     // unweighted, nominal robot
  int heldout_fk_failed = 0;        // held-out poses where FK did not converge
};

struct StudyRecord {
  std::string created;  // UTC, ISO 8601
  std::string session, robot, length_unit;
  int measured = 0;  // M: poses with a usable board pose
  int unusable = 0;  // rows left out without one
  // The request (workflow/study_options.h).
  int select = 0, subsets = 0, starts = 1;
  Criterion criterion = Criterion::kO1;
  std::optional<Criterion> secondary;
  bool weighted_selection = true;
  uint64_t seed = 1;
  StudySelection selected;
  int random_count = 0;              // K
  int random_failed = 0;             // random subsets not calibrated or validated
  std::string first_failure;         // the first of them, "subset k: why"
  std::vector<StudyMetric> metrics;  // one per kSubsetMetrics, in that order
  std::vector<std::string> figures;  // files written under --plots
  int threads = 0;
  double subsets_seconds = 0, seconds = 0;
  // What it was made from: the session's inputs as the study read them
  // (HashSessionInputs), to tell a study of inputs changed since (stale).
  ContentHashes inputs;
  std::string saved;  // the study folder it is kept in (DIR/study); empty: not kept (--no-save)

  const StudyMetric& Metric(SubsetMetric metric) const;  // asserts it is there
};

nlohmann::json ToJson(const StudyRecord& record);
StatusOr<StudyRecord> StudyRecordFromJson(const nlohmann::json& json, const std::string& source);

// Where the selected subset ranks, one sentence for the terminal, the report
// and the GUI: "the selected subset validates better than 95.6 % of the
// random subsets on the held-out position RMS, 99.8 % on the orientation
// RMS", or "warning: the selected subset could not be calibrated: ...".
std::string StudyRankSentence(const StudyRecord& record);

}  // namespace hexcal::workflow

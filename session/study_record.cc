#include "session/study_record.h"

#include <cassert>
#include <cmath>
#include <cstdio>

#include "session/json_fields.h"
#include "session/json_forms.h"

namespace hexcal::workflow {
namespace {

// Increased when a key changes meaning; a reader refuses other formats.
constexpr int kStudyFormat = 1;

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json DistributionJson(const Distribution& d) {
  return {{"count", d.count}, {"min", d.min}, {"p5", d.p5},   {"p25", d.p25},   {"median", d.median},
          {"p75", d.p75},     {"p95", d.p95}, {"max", d.max}, {"mean", d.mean}, {"std", d.std}};
}

Distribution DistributionFromJson(JsonFields fields) {
  Distribution d;
  d.count = fields.Int("count");
  double* values[] = {&d.min, &d.p5, &d.p25, &d.median, &d.p75, &d.p95, &d.max, &d.mean, &d.std};
  const char* keys[] = {"min", "p5", "p25", "median", "p75", "p95", "max", "mean", "std"};
  for (int k = 0; k < 9; ++k) *values[k] = fields.Number(keys[k]);
  return d;
}

nlohmann::json SelectedJson(const StudyRecord& record) {
  const StudySelection& selected = record.selected;
  nlohmann::json percentiles;
  for (const StudyMetric& m : record.metrics) {
    percentiles[SubsetMetricName(m.metric)] = std::isfinite(m.selected) ? nlohmann::json(m.percentile) : nullptr;
  }
  const char* position = SubsetMetricName(SubsetMetric::kHeldOutPosition);
  return {{"poses", selected.poses},
          {"images", selected.images},
          {"iterations", selected.iterations},
          {"ok", selected.ok},
          {"failure", selected.ok ? nlohmann::json(nullptr) : nlohmann::json(selected.failure)},
          {"indices", IndicesJson(selected.indices)},
          {"heldout_position_rms", NumberOrNull(record.Metric(SubsetMetric::kHeldOutPosition).selected)},
          {"heldout_orientation_rms", NumberOrNull(record.Metric(SubsetMetric::kHeldOutOrientation).selected)},
          {"heldout_fk_failed", selected.heldout_fk_failed},
          {"percentile", percentiles.value(position, nlohmann::json(nullptr))},
          {"percentiles", percentiles}};
}

nlohmann::json RandomJson(const StudyRecord& record) {
  nlohmann::json random = {
      {"count", record.random_count},
      {"failed", record.random_failed},
      {"first_failure", record.random_failed > 0 ? nlohmann::json(record.first_failure) : nullptr}};
  for (const StudyMetric& m : record.metrics) random[SubsetMetricName(m.metric)] = DistributionJson(m.random);
  return random;
}

ObservabilityIndices IndicesFromJson(JsonFields fields) {
  ObservabilityIndices o;
  o.o1 = fields.Number("O1");
  o.o2 = fields.Number("O2");
  o.o3 = fields.Number("O3");
  o.o4 = fields.Number("O4");
  o.sigma_min = fields.Number("sigma_min");
  o.sigma_max = fields.Number("sigma_max");
  o.num_poses = fields.Int("poses");
  return o;
}

StudySelection SelectionFromJson(JsonFields fields) {
  StudySelection s;
  s.poses = fields.Ints("poses");
  s.images = fields.Strings("images");
  s.iterations = fields.Int("iterations");
  s.ok = fields.Bool("ok");
  if (!s.ok) s.failure = fields.Has("failure") ? fields.String("failure") : "";
  s.indices = IndicesFromJson(fields.Object("indices"));
  s.heldout_fk_failed = fields.Int("heldout_fk_failed");
  if (s.images.size() != s.poses.size()) fields.Fail("images", "expected one image per pose");
  return s;
}

// The selected value of each metric: its index, or its held-out error (null
// when its calibration failed); the rank from "percentiles".
std::vector<StudyMetric> MetricsFromJson(JsonFields selected, JsonFields random, const StudySelection& selection) {
  JsonFields percentiles = selected.Object("percentiles");
  SubsetOutcome indices_only;
  indices_only.indices = selection.indices;
  std::vector<StudyMetric> metrics;
  for (SubsetMetric metric : kSubsetMetrics) {
    const std::string name = SubsetMetricName(metric);
    StudyMetric m{metric, 0, DistributionFromJson(random.Object(name)), 0};
    if (HigherIsBetter(metric)) {
      m.selected = MetricValue(indices_only, metric);
    } else {
      m.selected = selected.OptionalNumber(name).value_or(std::nan(""));
    }
    m.percentile = percentiles.OptionalNumber(name).value_or(0);
    metrics.push_back(m);
  }
  return metrics;
}

std::optional<Criterion> CriterionFromJson(JsonFields& fields, const std::string& key) {
  const std::string name = fields.String(key);
  const std::optional<Criterion> criterion = ParseCriterion(name);
  if (!criterion && fields.status().ok()) fields.Fail(key, "'" + name + "' is not a criterion");
  return criterion;
}

}  // namespace

const StudyMetric& StudyRecord::Metric(SubsetMetric metric) const {
  for (const StudyMetric& m : metrics)
    if (m.metric == metric) return m;
  assert(false && "a study record has every metric");
  return metrics.front();
}

nlohmann::json ToJson(const StudyRecord& record) {
  return {{"format", kStudyFormat},
          {"created", record.created},
          {"session", record.session},
          {"robot", record.robot},
          {"length_unit", record.length_unit},
          {"measured", record.measured},
          {"unusable", record.unusable},
          {"select", record.select},
          {"subsets", record.subsets},
          {"criterion", CriterionName(record.criterion)},
          {"secondary", record.secondary ? nlohmann::json(CriterionName(*record.secondary)) : nullptr},
          {"starts", record.starts},
          {"weighted_selection", record.weighted_selection},
          {"seed", record.seed},
          {"selected", SelectedJson(record)},
          {"random", RandomJson(record)},
          {"figures", record.figures},
          {"threads", record.threads},
          {"subsets_seconds", record.subsets_seconds},
          {"seconds", record.seconds},
          {"inputs", record.inputs},
          {"saved", record.saved.empty() ? nlohmann::json(nullptr) : nlohmann::json(record.saved)}};
}

StatusOr<StudyRecord> StudyRecordFromJson(const nlohmann::json& json, const std::string& source) {
  JsonFields fields(json, source);
  if (!fields.status().ok()) return fields.status();
  if (const int format = fields.Int("format"); fields.status().ok() && format != kStudyFormat)
    return Status::BadInput(source + ": format " + std::to_string(format) + " is not " + std::to_string(kStudyFormat) +
                            " (written by another hexcal): run hexcal study again");
  StudyRecord r;
  r.created = fields.String("created");
  r.session = fields.String("session");
  r.robot = fields.String("robot");
  r.length_unit = fields.String("length_unit");
  r.measured = fields.Int("measured");
  r.unusable = fields.Int("unusable");
  r.select = fields.Int("select");
  r.subsets = fields.Int("subsets");
  r.starts = fields.Int("starts");
  r.criterion = CriterionFromJson(fields, "criterion").value_or(Criterion::kO1);
  if (fields.Has("secondary")) r.secondary = CriterionFromJson(fields, "secondary");
  r.weighted_selection = fields.Bool("weighted_selection");
  r.seed = static_cast<uint64_t>(fields.Number("seed"));
  r.selected = SelectionFromJson(fields.Object("selected"));
  JsonFields random = fields.Object("random");
  r.random_count = random.Int("count");
  r.random_failed = random.Int("failed");
  if (r.random_failed > 0) r.first_failure = random.String("first_failure");
  r.metrics = MetricsFromJson(fields.Object("selected"), random, r.selected);
  r.figures = fields.Strings("figures");
  r.threads = fields.Int("threads");
  r.subsets_seconds = fields.Number("subsets_seconds");
  r.seconds = fields.Number("seconds");
  if (fields.Has("saved")) r.saved = fields.String("saved");
  if (!fields.status().ok()) return fields.status();
  if (Status s = ReadContentHashes(json, "inputs", source, &r.inputs); !s.ok()) return s;
  return r;
}

std::string StudyRankSentence(const StudyRecord& record) {
  if (!record.selected.ok) return "warning: the selected subset could not be calibrated: " + record.selected.failure;
  char line[200];
  std::snprintf(line, sizeof line,
                "the selected subset validates better than %.1f %% of the random subsets on the held-out position "
                "RMS, %.1f %% on the orientation RMS",
                record.Metric(SubsetMetric::kHeldOutPosition).percentile,
                record.Metric(SubsetMetric::kHeldOutOrientation).percentile);
  return line;
}

}  // namespace hexcal::workflow

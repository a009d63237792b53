#include "session/session_results.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/noise_model.h"
#include "core/session.h"
#include "core/sha256.h"
#include "session/json_fields.h"
#include "session/results_files.h"
#include "session/session_models.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

constexpr int kManifestFormat = 1;
constexpr const char* kConfigInputs = "session.yaml (robot, camera, target, noise)";

// A points session's inputs: the robot, the points file and the reflector
// file (when given), and its keys of session.yaml.
StatusOr<std::string> HashPointConfigInputs(const std::string& dir, const SessionConfig& config,
                                            ContentHashes* hashes) {
  StatusOr<std::string> robot = HashSessionFile(dir, config.robot);
  if (!robot.ok()) return robot.status();
  (*hashes)["robot " + config.robot] = *robot;
  for (const auto& [kind, name] : {std::pair{"points ", &config.points}, std::pair{"reflectors ", &config.reflectors}}) {
    if (name->empty()) continue;
    StatusOr<std::string> hash = Sha256OfFile(ResolveSessionFile(dir, *name), kMaxTableBytes);
    if (!hash.ok()) return hash.status();
    (*hashes)[kind + *name] = *hash;
  }
  const std::string check = SessionPaths(dir).noise_check;  // hexcal session check-noise's
  std::error_code error;
  if (fs::exists(fs::symlink_status(check, error))) {
    StatusOr<std::string> hash = Sha256OfFile(check, kMaxYamlBytes);
    if (!hash.ok()) return hash.status();
    (*hashes)[kNoiseCheckFile] = *hash;
  }
  return Sha256Hex("robot: " + config.robot + "\ninstrument: points\npoints: " + config.points +
                   "\nreflectors: " + config.reflectors + "\npoint_sigma: " + FormatNumber(config.point_sigma) +
                   "\nnoise: " + NoiseModelText(config.noise) + "\n");
}

StatusOr<std::string> HashConfigInputs(const std::string& dir, const SessionConfig& config, ContentHashes* hashes) {
  if (config.instrument == Instrument::kPoints) return HashPointConfigInputs(dir, config, hashes);
  const std::pair<const char*, const std::string*> named[] = {
      {"robot ", &config.robot}, {"camera ", &config.camera}, {"target ", &config.target}};
  for (const auto& [kind, name] : named) {
    StatusOr<std::string> hash = HashSessionFile(dir, *name);
    if (!hash.ok()) return hash.status();
    (*hashes)[kind + *name] = *hash;
  }
  // The frames in session.yaml are outputs of the run, not inputs: left out.
  return Sha256Hex("robot: " + config.robot + "\ncamera: " + config.camera + "\ntarget: " + config.target +
                   "\nnoise: " + NoiseModelText(config.noise) + "\n");
}

// Every output of the manifest has the hash it had when the run published it.
Status CheckOutputs(const std::string& dir, const ResultsManifest& manifest) {
  const std::string results = SessionPaths(dir).results;
  for (const char* name : {kReportJson, kCalibratedRobot, kUsedMeasurements})
    if (manifest.outputs.count(name) == 0) return Status::BadInput(ResultsManifestPath(dir) + ": lists no " + name);
  // camera.yaml and corner_residuals.csv: the intrinsics a calibration from
  // pixels estimated and its corners' residuals; reflectors.csv and
  // point_residuals.csv: the calibration from points' (docs/session.md).
  size_t optional = 0;
  for (const char* name : {kFittedCamera, kCornerResiduals, kFittedReflectors, kPointResiduals})
    optional += manifest.outputs.count(name);
  if (manifest.outputs.size() != 3 + optional)
    return Status::BadInput(ResultsManifestPath(dir) + ": lists other outputs");
  for (const auto& [name, expected] : manifest.outputs) {
    const std::string path = (fs::path(results) / name).string();
    StatusOr<std::string> hash = Sha256OfFile(path, kMaxTableBytes);
    if (!hash.ok() || *hash != expected) {
      return Status::BadInput(
          path + ": does not match " + ResultsManifestPath(dir) +
          " (changed or replaced after the run that wrote results/); run `hexcal calibrate --session " + dir +
          "` again");
    }
  }
  return Status::Ok();
}

}  // namespace

Status ReadContentHashes(const nlohmann::json& json, const char* key, const std::string& source, ContentHashes* out) {
  const auto found = json.find(key);
  if (found == json.end() || !found->is_object())
    return Status::BadInput(source + ": " + key + ": missing or not an object");
  for (const auto& [name, hash] : found->items()) {
    if (!hash.is_string() || hash.get<std::string>().size() != 64) {
      return Status::BadInput(source + ": " + key + "." + name + ": not a SHA-256 hex digest");
    }
    (*out)[name] = hash.get<std::string>();
  }
  return Status::Ok();
}

StatusOr<std::string> HashSessionFile(const std::string& dir, const std::string& name) {
  const std::string resolved = ResolveSessionFile(dir, name);
  std::error_code error;
  if (!fs::exists(resolved, error)) return Sha256Hex("preset " + name);
  return Sha256OfFile(resolved, kMaxYamlBytes);
}

std::string ResultsManifestPath(const std::string& session_dir) {
  return ResultsFile(session_dir, kResultsManifest);
}

std::string ManifestToJsonText(const ResultsManifest& manifest) {
  const nlohmann::json json{{"format", kManifestFormat},
                            {"created", manifest.created},
                            {"command", manifest.command},
                            {"inputs", manifest.inputs},
                            {"outputs", manifest.outputs}};
  // A file name that is not UTF-8 (a Latin-1 share) is written with U+FFFD, never thrown on.
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

StatusOr<ResultsManifest> ParseResultsManifest(const std::string& text, const std::string& source) {
  StatusOr<nlohmann::json> json = ParseJsonText(text, source);
  if (!json.ok()) return json.status();
  if (!json->is_object()) return Status::BadInput(source + ": not a JSON object");
  JsonFields fields(*json, source);
  ResultsManifest manifest;
  const int format = fields.Int("format");
  manifest.created = fields.String("created");
  manifest.command = fields.String("command");
  if (!fields.status().ok()) return fields.status();
  if (format != kManifestFormat) return Status::BadInput(source + ": format " + std::to_string(format) + " is not 1");
  if (Status s = ReadContentHashes(*json, "inputs", source, &manifest.inputs); !s.ok()) return s;
  if (Status s = ReadContentHashes(*json, "outputs", source, &manifest.outputs); !s.ok()) return s;
  return manifest;
}

StatusOr<ContentHashes> HashSessionInputs(const std::string& dir) {
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  ContentHashes hashes;
  StatusOr<std::string> config_hash = HashConfigInputs(dir, *config, &hashes);
  if (!config_hash.ok()) return config_hash.status();
  hashes[kConfigInputs] = *config_hash;
  const SessionPaths paths(dir);
  StatusOr<std::string> legs = Sha256OfFile(paths.legs, kMaxTableBytes);
  if (!legs.ok()) return legs.status();
  hashes["legs.csv"] = *legs;
  if (config->instrument == Instrument::kPoints) return hashes;  // no images: the points file is hashed above
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(dir);
  if (!rows.ok()) return rows.status();
  for (const LegsRow& row : *rows) {
    StatusOr<std::string> image = Sha256OfFile((fs::path(paths.images) / row.image).string(), kMaxImageBytes);
    if (!image.ok()) return image.status();
    hashes["images/" + row.image] = *image;
  }
  return hashes;
}

std::vector<std::string> DifferingNames(const ContentHashes& a, const ContentHashes& b) {
  std::vector<std::string> names;
  for (const auto& [name, hash] : a) {
    const auto found = b.find(name);
    if (found == b.end() || found->second != hash) names.push_back(name);
  }
  for (const auto& [name, hash] : b)
    if (a.count(name) == 0) names.push_back(name);
  return names;
}

StatusOr<SessionResults> LoadSessionResults(const std::string& dir, const ContentHashes* inputs) {
  const std::string manifest_path = ResultsManifestPath(dir);
  std::error_code error;
  if (!fs::exists(manifest_path, error)) {
    return Status::BadInput(manifest_path +
                            ": missing: results/ was not written whole by `hexcal calibrate --session` "
                            "(an older hexcal, or files put there by hand); run it again");
  }
  StatusOr<std::string> text = ReadFileToString(manifest_path, kMaxJsonBytes);
  if (!text.ok()) return text.status();
  SessionResults results;
  StatusOr<ResultsManifest> manifest = ParseResultsManifest(*text, manifest_path);
  if (!manifest.ok()) return manifest.status();
  results.manifest = *manifest;
  if (Status s = CheckOutputs(dir, results.manifest); !s.ok()) return s;
  StatusOr<CalibrationReport> report = LoadCalibrationReport(CalibrationReportPath(dir));
  if (!report.ok()) return report.status();
  results.report = *report;
  StatusOr<ContentHashes> now = inputs ? StatusOr<ContentHashes>(*inputs) : HashSessionInputs(dir);
  results.changed_inputs = now.ok() ? DifferingNames(results.manifest.inputs, *now) : std::vector<std::string>{"session"};
  return results;
}

std::string ListNames(const std::vector<std::string>& names) {
  constexpr size_t kShown = 3;
  std::string text;
  for (size_t i = 0; i < names.size() && i < kShown; ++i) {
    text += (i == 0 ? "" : (i + 1 == names.size() ? " and " : ", ")) + names[i];
  }
  if (names.size() > kShown) text += " and " + std::to_string(names.size() - kShown) + " more";
  return text;
}

}  // namespace hexcal::workflow

// results/ as one unit (issue 13; docs/session.md, "Results as one unit"):
// `calibrate --session` writes its files into a fresh folder with a manifest of
// the content hashes (SHA-256) of what it read and of what it wrote, and swaps
// it in whole (core/staged_folder.h). Readers go through LoadSessionResults,
// which checks every output against the manifest: a results/ mixed from two
// runs, edited by hand or written by an older hexcal is refused, by name.
//
//   StatusOr<SessionResults> results = LoadSessionResults("run1");
//   if (results.ok() && !results->changed_inputs.empty()) ...  // stale: legs.csv changed since
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "session/calibration_report.h"

namespace hexcal::workflow {

// Name → SHA-256. Inputs are named as in the session: "legs.csv",
// "images/img_000.png", "session.yaml (robot, camera, target, noise)", and
// "robot <name>", "camera <name>", "target <name>" for the files (or presets)
// session.yaml names; outputs are the file names inside results/.
using ContentHashes = std::map<std::string, std::string>;

struct ResultsManifest {
  std::string created;  // UTC, ISO 8601
  std::string command;  // what wrote it: "calibrate --session"
  ContentHashes inputs;
  ContentHashes outputs;
};

std::string ResultsManifestPath(const std::string& session_dir);  // DIR/results/manifest.json
std::string ManifestToJsonText(const ResultsManifest& manifest);
StatusOr<ResultsManifest> ParseResultsManifest(const std::string& text, const std::string& source);

// The hash of a file session.yaml names (robot, camera, target): its bytes, or
// the name itself when it names a preset compiled into hexcal.
StatusOr<std::string> HashSessionFile(const std::string& session_dir, const std::string& name);

// The hashes of everything a calibration of the session reads.
StatusOr<ContentHashes> HashSessionInputs(const std::string& session_dir);
// Reads `json[key]`, an object of name → SHA-256 hex digest, into `out`.
Status ReadContentHashes(const nlohmann::json& json, const char* key, const std::string& source, ContentHashes* out);
// The names whose hash differs between two sets, or that only one set has.
std::vector<std::string> DifferingNames(const ContentHashes& a, const ContentHashes& b);

struct SessionResults {
  ResultsManifest manifest;
  CalibrationReport report;
  // Inputs that changed since the run (the results are stale), by name.
  std::vector<std::string> changed_inputs;
};

// Reads results/manifest.json, checks every output's hash, reads report.json
// and compares the inputs with the session as it is now (`inputs`, when the
// caller hashed them already: HashSessionInputs).
StatusOr<SessionResults> LoadSessionResults(const std::string& session_dir, const ContentHashes* inputs = nullptr);

// "legs.csv, images/img_004.png and 3 more": a short list for messages.
std::string ListNames(const std::vector<std::string>& names);

}  // namespace hexcal::workflow

// Reading a JSON document written by hexcal back into typed values, with
// errors that name the file, the key path and the problem, never the
// document's content, and never an exception or an abort.
//
//   JsonFields fields(document, "results/report.json");
//   const int images = fields.Int("images");
//   const double rms = fields.Object("registration").Number("position_rms");
//   if (!fields.status().ok()) return fields.status();
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"

namespace hexcal::workflow {

class JsonFields {
 public:
  // `source` names the document in errors (a file path).
  JsonFields(const nlohmann::json& node, std::string source);

  double Number(const std::string& key);
  std::optional<double> OptionalNumber(const std::string& key);  // null or missing: nullopt
  int Int(const std::string& key);
  bool Bool(const std::string& key);
  std::string String(const std::string& key);
  std::vector<double> Numbers(const std::string& key, size_t count);  // exactly `count`
  std::vector<int> Ints(const std::string& key);                      // any length
  std::vector<std::string> Strings(const std::string& key);           // any length
  bool Has(const std::string& key) const;  // present and not null
  // Nested readers share the first error with this one.
  JsonFields Object(const std::string& key);
  std::vector<JsonFields> Array(const std::string& key);

  // Records a problem with `key` found by the caller (e.g. an unknown name).
  void Fail(const std::string& key, const std::string& problem);

  // The first problem met, or OK.
  Status status() const { return *first_error_; }

 private:
  JsonFields(const nlohmann::json* node, std::string source, std::string path, std::shared_ptr<Status> first_error);
  const nlohmann::json* Field(const std::string& key, const char* expected);
  std::string PathOf(const std::string& key) const;

  const nlohmann::json* node_;
  std::string source_, path_;
  std::shared_ptr<Status> first_error_;
};

// Parses `text` as JSON without exceptions; the error names `source` only.
StatusOr<nlohmann::json> ParseJsonText(const std::string& text, const std::string& source);

}  // namespace hexcal::workflow

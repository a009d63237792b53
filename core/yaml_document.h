// Reading a YAML file's text into a document, the same way for every hexcal
// file format (robot, session, target, camera): a syntax error becomes a
// Status that names the file, the line and the column, and a yaml-cpp
// exception that escapes a reader's checks becomes a Status rather than a
// crash.
//
//   StatusOr<YAML::Node> root = LoadYamlDocument(text, "robot file 'r.yaml'");
//   if (!root.ok()) return root.status();  // "robot file 'r.yaml': YAML syntax error at line 3, column 7: ..."
//   return WithYamlBackstop<Robot>("robot file 'r.yaml'", [&] { return ReadRoot(*root); });
//
// yaml-cpp stays a private dependency of core: only the layers that link it
// themselves (core, vision) include this header.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

#include "core/status.h"

namespace hexcal {

// `label` starts every message, e.g. "target file 'board.yaml'". A mapping
// that names a key twice is refused: "...: camera_matrix.rows: duplicate key (lines 3 and 7)".
StatusOr<YAML::Node> LoadYamlDocument(const std::string& text, const std::string& label);

// A mapping's key as an error may show it: the key itself when it is a name
// (IsPlainName, core/csv.h), else "the key on line N". A file named in place
// of a robot or a target (/etc/shadow) had its first line echoed as the
// "unknown key" (issue 36); errors name keys, never contents.
std::string YamlKeyText(const YAML::Node& key);

// The (key, scalar text) entries of a mapping, for ApplyOptionEntries
// (core/option_spec.h); `where` names the section in errors ("plan.yaml: noise").
StatusOr<std::vector<std::pair<std::string, std::string>>> ScalarEntries(const YAML::Node& map,
                                                                         const std::string& where);

// read() with every YAML::Exception it throws turned into "<label>: <what>".
// Readers check each access; this is the backstop for the one they miss.
template <typename T, typename Read>
StatusOr<T> WithYamlBackstop(const std::string& label, Read read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    return Status::BadInput(label + ": " + e.what());
  }
}

}  // namespace hexcal

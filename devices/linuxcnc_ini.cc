#include "devices/linuxcnc_ini.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>

namespace hexcal::workflow {
namespace {

constexpr const char* kJointKeys[4] = {"HOME", "HOME_OFFSET", "MIN_LIMIT", "MAX_LIMIT"};

std::string Trim(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// One line: a section header, a KEY = VALUE or neither (a comment, a blank).
struct IniLine {
  std::string section;  // set on a header line
  std::string key, value;
  size_t value_start = 0;  // where the value begins in the line
};

IniLine ParseLine(const std::string& line) {
  IniLine parsed;
  const std::string trimmed = Trim(line);
  if (trimmed.empty() || trimmed[0] == '#' || trimmed[0] == ';') return parsed;
  if (trimmed.front() == '[' && trimmed.back() == ']') {
    parsed.section = trimmed.substr(1, trimmed.size() - 2);
    return parsed;
  }
  const size_t equals = line.find('=');
  if (equals == std::string::npos) return parsed;
  parsed.key = Trim(line.substr(0, equals));
  parsed.value_start = line.find_first_not_of(" \t", equals + 1);
  if (parsed.value_start == std::string::npos) parsed.value_start = line.size();
  parsed.value = Trim(line.substr(parsed.value_start));
  return parsed;
}

// The joint number of a [JOINT_n] section with n in 0..5, or -1.
int JointNumber(const std::string& section) {
  if (section.size() != 7 || section.rfind("JOINT_", 0) != 0) return -1;
  const char digit = section[6];
  return digit >= '0' && digit <= '5' ? digit - '0' : -1;
}

int JointKeyIndex(const std::string& key) {
  for (int k = 0; k < 4; ++k)
    if (key == kJointKeys[k]) return k;
  return -1;
}

std::optional<double> DecimalNumber(const std::string& text) {
  if (text.empty() || text.find_first_not_of("+-0123456789.") != std::string::npos) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || *end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

double& JointValue(IniJoint& joint, int key) {
  double* values[4] = {&joint.home, &joint.home_offset, &joint.min_limit, &joint.max_limit};
  return *values[key];
}

}  // namespace

StatusOr<MachineIni> ParseMachineIni(const std::string& text) {
  MachineIni ini;
  ini.text = text;
  std::map<std::string, int> seen;  // "SECTION KEY" of the keys read, and how often
  std::optional<std::string> units;
  std::istringstream lines(text);
  std::string section;
  for (std::string line; std::getline(lines, line);) {
    const IniLine parsed = ParseLine(line);
    if (!parsed.section.empty()) section = parsed.section;
    const int joint = JointNumber(section), key = JointKeyIndex(parsed.key);
    if (section == "HAL" && parsed.key == "HALFILE") ini.hal_files.push_back(parsed.value);
    const bool wanted = (section == "TRAJ" && parsed.key == "LINEAR_UNITS") || (joint >= 0 && key >= 0);
    if (parsed.key.empty() || !wanted) continue;
    const std::string where = "[" + section + "] " + parsed.key;
    if (++seen[where] > 1) return Status::BadInput("INI: " + where + " is given twice; keep one");
    if (joint < 0) {
      units = parsed.value;
      continue;
    }
    const std::optional<double> value = DecimalNumber(parsed.value);
    if (!value) return Status::BadInput("INI: " + where + " is not a decimal number");
    JointValue(ini.joints[joint], key) = *value;
  }
  if (!units) return Status::BadInput("INI: no [TRAJ] LINEAR_UNITS");
  const std::optional<MachineUnit> unit = ParseMachineUnit(*units);
  if (!unit) return Status::BadInput("INI: [TRAJ] LINEAR_UNITS is not mm or inch");
  ini.unit = *unit;
  for (int joint = 0; joint < 6; ++joint)
    for (const char* key : kJointKeys)
      if (!seen.count("[JOINT_" + std::to_string(joint) + "] " + key))
        return Status::BadInput("INI: no [JOINT_" + std::to_string(joint) + "] " + key +
                                " (a genhexkins machine has six joints, each with its home and limits)");
  return ini;
}

std::string ShiftedIniText(const MachineIni& ini, const std::array<double, 6>& shifts) {
  std::string out;
  std::istringstream lines(ini.text);
  std::string section;
  for (std::string line; std::getline(lines, line);) {
    const IniLine parsed = ParseLine(line);
    if (!parsed.section.empty()) section = parsed.section;
    const int joint = JointNumber(section), key = JointKeyIndex(parsed.key);
    if (joint >= 0 && key >= 0) {
      IniJoint values = ini.joints[joint];
      const std::string ending = !line.empty() && line.back() == '\r' ? "\r" : "";
      line = line.substr(0, parsed.value_start) + ExactFixedNumber(JointValue(values, key) + shifts[joint]) + ending;
    }
    out += line + "\n";
  }
  if (!ini.text.empty() && ini.text.back() != '\n') out.pop_back();
  return out;
}

std::string IniChangeText(const MachineIni& ini, const std::array<double, 6>& shifts) {
  std::ostringstream out;
  for (int joint = 0; joint < 6; ++joint) {
    if (shifts[joint] == 0) continue;
    IniJoint values = ini.joints[joint];
    for (int key = 0; key < 4; ++key)
      out << "[JOINT_" << joint << "] " << kJointKeys[key] << " " << ExactFixedNumber(JointValue(values, key))
          << " -> " << ExactFixedNumber(JointValue(values, key) + shifts[joint]) << "\n";
  }
  return out.str();
}

}  // namespace hexcal::workflow

#include "core/robot_io.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/presets.h"
#include "core/yaml_document.h"

namespace hexcal {
namespace {

const std::vector<std::string> kTopKeys = {"name", "length_unit", "euler", "legs", "limits", "calibration"};
const std::vector<std::string> kRequiredTopKeys = {"name", "length_unit", "euler", "legs"};
const std::vector<std::string> kLegKeys = {"a", "b", "l", "stroke"};
const std::vector<std::string> kLimitKeys = {"base_joint_max_deg", "platform_joint_max_deg", "leg_min_distance",
                                             "assembly_mode", "pose_box", "sampling_box"};
const std::vector<std::string> kAssemblyModeKeys = {"pose", "min_det_ratio"};
// In the order of the pose vector [x, y, z, q1, q2, q3].
const std::vector<std::string> kPoseBoxKeys = {"x", "y", "z", "q1", "q2", "q3"};

// Two attachment points closer than this, relative to the robot's size, are
// one point: in a 6-6 file that is a copy-paste slip, not a design.
constexpr double kCoincidenceTolerance = 1e-9;

std::string Join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string joined;
  for (size_t i = 0; i < parts.size(); ++i) joined += (i ? separator : "") + parts[i];
  return joined;
}

std::string Child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::string Indexed(const std::string& path, size_t index) { return path + "[" + std::to_string(index) + "]"; }

// How a value the reader did not expect looks, for "expected X, found Y".
std::string Describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return Excerpt(node.Scalar());
}

bool IsQuotedOrString(const YAML::Node& node) { return node.Tag() == "!" || node.Tag() == "tag:yaml.org,2002:str"; }

// Reads one robot document; every message starts with `label`, which says
// where the text came from.
class RobotYamlReader {
 public:
  explicit RobotYamlReader(std::string label) : label_(std::move(label)) {}

  StatusOr<Robot> Read(const std::string& text) const {
    const StatusOr<YAML::Node> root = LoadYamlDocument(text, label_);
    if (!root.ok()) return root.status();
    return WithYamlBackstop<Robot>(label_, [&] { return ReadRoot(*root); });
  }

 private:
  Status Error(const std::string& key_path, const std::string& problem) const {
    return Status::BadInput(label_ + ": " + key_path + ": " + problem);
  }

  StatusOr<Robot> ReadRoot(const YAML::Node& root) const {
    if (!root.IsMap()) {
      return Error("top level",
                   "expected a mapping with keys " + Join(kRequiredTopKeys, ", ") + ", found " + Describe(root));
    }
    if (Status s = CheckKeys(root, "", kTopKeys, kRequiredTopKeys); !s.ok()) return s;
    Robot robot;
    StatusOr<std::string> name = Text(root["name"], "name");
    if (!name.ok()) return name.status();
    if (name->find_first_not_of(" \t") == std::string::npos) {
      return Error("name", "must not be empty");
    }
    robot.name = *name;

    StatusOr<std::string> unit = Text(root["length_unit"], "length_unit");
    if (!unit.ok()) return unit.status();
    const std::optional<LengthUnit> length_unit = ParseLengthUnit(*unit);
    if (!length_unit) {
      return Error("length_unit", "unknown unit '" + *unit + "' (allowed: mm, cm, m)");
    }
    robot.length_unit = *length_unit;

    StatusOr<std::string> euler = Text(root["euler"], "euler");
    if (!euler.ok()) return euler.status();
    const std::optional<EulerConvention> convention = ParseEulerConvention(*euler);
    if (!convention) {
      return Error("euler", "unknown convention '" + *euler + "' (allowed: xyz, zyx)");
    }
    robot.euler = *convention;

    if (Status s = ReadLegs(root["legs"], &robot); !s.ok()) return s;
    if (Status s = ReadLimits(root["limits"], &robot.limits); !s.ok()) return s;
    if (Status s = CheckAssemblyModePose(robot); !s.ok()) return s;
    // root["calibration"] is written by `hexcal calibrate` for people and tools
    // that audit a result; the robot model does not use it.
    return robot;
  }

  // Rejects non-scalar, duplicate and unknown keys, then missing required ones;
  // an unknown key first, since it is usually a misspelt required one.
  Status CheckKeys(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed,
                   const std::vector<std::string>& required) const {
    std::set<std::string> seen;
    for (const auto& entry : map) {
      if (!entry.first.IsScalar()) {
        return Error(path.empty() ? "top level" : path, "a key is " + Describe(entry.first));
      }
      const std::string& key = entry.first.Scalar();
      if (!seen.insert(key).second) return Error(Child(path, YamlKeyText(entry.first)), "duplicate key");
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        return Error(Child(path, YamlKeyText(entry.first)), "unknown key (allowed: " + Join(allowed, ", ") + ")");
      }
    }
    for (const std::string& key : required) {
      if (!seen.count(key)) return Error(Child(path, key), "required key is missing");
    }
    return Status::Ok();
  }

  StatusOr<std::string> Text(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) return Error(path, "expected text, found " + Describe(node));
    return node.Scalar();
  }

  StatusOr<double> Number(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) return Error(path, "expected a number, found " + Describe(node));
    // A quoted "5" is text in YAML; accepting it would hide a file edited wrongly.
    if (IsQuotedOrString(node)) {
      return Error(path, "expected a number, found the text '" + node.Scalar() + "'");
    }
    StatusOr<double> value = ParseNumber(node.Scalar());
    if (!value.ok()) return Error(path, value.status().message());
    return value;
  }

  // A list of exactly `count` numbers; `form` shows the expected list.
  StatusOr<std::vector<double>> Numbers(const YAML::Node& node, const std::string& path, size_t count,
                                        const std::string& form) const {
    const std::string expected = "expected " + std::to_string(count) + " numbers " + form;
    if (!node.IsSequence()) return Error(path, expected + ", found " + Describe(node));
    if (node.size() != count) {
      return Error(path, expected + ", found " + std::to_string(node.size()));
    }
    std::vector<double> values;
    for (size_t i = 0; i < count; ++i) {
      StatusOr<double> value = Number(node[i], Indexed(path, i));
      if (!value.ok()) return value.status();
      values.push_back(*value);
    }
    return values;
  }

  StatusOr<Eigen::Vector3d> Point(const YAML::Node& node, const std::string& path) const {
    StatusOr<std::vector<double>> xyz = Numbers(node, path, 3, "[x, y, z]");
    if (!xyz.ok()) return xyz.status();
    return Eigen::Vector3d((*xyz)[0], (*xyz)[1], (*xyz)[2]);
  }

  StatusOr<Range> MinMax(const YAML::Node& node, const std::string& path) const {
    StatusOr<std::vector<double>> bounds = Numbers(node, path, 2, "[min, max]");
    if (!bounds.ok()) return bounds.status();
    const Range range{(*bounds)[0], (*bounds)[1]};
    if (range.min >= range.max) {
      return Error(path,
                   "min (" + FormatNumber(range.min) + ") must be less than max (" + FormatNumber(range.max) + ")");
    }
    return range;
  }

  Status ReadLegs(const YAML::Node& legs, Robot* robot) const {
    if (!legs.IsSequence()) {
      return Error("legs", "expected a list of 6 legs, found " + Describe(legs));
    }
    if (legs.size() != static_cast<size_t>(kNumLegs)) {
      return Error("legs", "expected exactly 6 legs, found " + std::to_string(legs.size()));
    }
    for (size_t i = 0; i < legs.size(); ++i) {
      if (Status s = ReadLeg(legs[i], Indexed("legs", i), &robot->legs[i]); !s.ok()) return s;
    }
    return CheckDistinctAttachments(*robot);
  }

  Status ReadLeg(const YAML::Node& node, const std::string& path, Leg* leg) const {
    if (!node.IsMap()) {
      const std::string form = "{a: [x, y, z], b: [x, y, z], l: offset, stroke: [min, max]}";
      return Error(path, "expected a mapping " + form + ", found " + Describe(node));
    }
    if (Status s = CheckKeys(node, path, kLegKeys, kLegKeys); !s.ok()) return s;
    StatusOr<Eigen::Vector3d> a = Point(node["a"], path + ".a");
    if (!a.ok()) return a.status();
    StatusOr<Eigen::Vector3d> b = Point(node["b"], path + ".b");
    if (!b.ok()) return b.status();
    StatusOr<double> offset = Number(node["l"], path + ".l");
    if (!offset.ok()) return offset.status();
    StatusOr<Range> stroke = MinMax(node["stroke"], path + ".stroke");
    if (!stroke.ok()) return stroke.status();
    // The offset alone may be negative (it depends on where the sensor's zero
    // is), but the physical leg, offset plus shortest reading, cannot.
    const double shortest = *offset + stroke->min;
    if (shortest <= 0) {
      return Error(path, "l + stroke min (" + FormatNumber(*offset) + " + " + FormatNumber(stroke->min) + " = " +
                             FormatNumber(shortest) + ") must be > 0: it is the shortest length of the leg");
    }
    *leg = Leg{*a, *b, *offset, stroke->min, stroke->max};
    return Status::Ok();
  }

  Status CheckDistinctAttachments(const Robot& robot) const {
    double scale = 0;
    for (const Leg& leg : robot.legs) {
      scale = std::max({scale, leg.a_in_base.norm(), leg.b_in_platform.norm(), leg.offset + leg.stroke_max});
    }
    const double tolerance = kCoincidenceTolerance * scale;
    for (int j = 1; j < kNumLegs; ++j) {
      for (int i = 0; i < j; ++i) {
        const Leg& first = robot.legs[i];
        const Leg& second = robot.legs[j];
        const std::string legs_i = Indexed("legs", i);
        const std::string legs_j = Indexed("legs", j);
        if ((first.a_in_base - second.a_in_base).norm() <= tolerance) {
          return Error(legs_j + ".a", "coincides with " + legs_i + ".a");
        }
        if ((first.b_in_platform - second.b_in_platform).norm() <= tolerance) {
          return Error(legs_j + ".b", "coincides with " + legs_i + ".b");
        }
      }
    }
    return Status::Ok();
  }

  // An absent or empty `limits:` means no limits.
  Status ReadLimits(const YAML::Node& node, RobotLimits* limits) const {
    if (!node.IsDefined() || node.IsNull()) return Status::Ok();
    if (!node.IsMap()) return Error("limits", "expected a mapping, found " + Describe(node));
    if (Status s = CheckKeys(node, "limits", kLimitKeys, {}); !s.ok()) return s;
    const std::pair<const char*, std::optional<double>*> joint_limits[] = {
        {"base_joint_max_deg", &limits->base_joint_max_deg},
        {"platform_joint_max_deg", &limits->platform_joint_max_deg}};
    for (const auto& [key, limit] : joint_limits) {
      if (!node[key]) continue;
      const std::string path = Child("limits", key);
      StatusOr<double> angle = Number(node[key], path);
      if (!angle.ok()) return angle.status();
      if (*angle <= 0 || *angle >= 180) {
        return Error(path, "must be in (0, 180) degrees, found " + FormatNumber(*angle));
      }
      *limit = *angle;
    }
    if (node["leg_min_distance"]) {
      StatusOr<double> distance = Number(node["leg_min_distance"], "limits.leg_min_distance");
      if (!distance.ok()) return distance.status();
      if (*distance < 0) {
        return Error("limits.leg_min_distance", "must be >= 0, found " + FormatNumber(*distance));
      }
      limits->leg_min_distance = *distance;
    }
    if (Status s = ReadAssemblyMode(node["assembly_mode"], &limits->assembly_mode); !s.ok()) return s;
    if (Status s = ReadPoseBox(node["pose_box"], "pose_box", &limits->pose_box); !s.ok()) return s;
    return ReadPoseBox(node["sampling_box"], "sampling_box", &limits->sampling_box);
  }

  Status ReadAssemblyMode(const YAML::Node& node, std::optional<AssemblyMode>* out) const {
    if (!node.IsDefined() || node.IsNull()) return Status::Ok();
    const std::string path = "limits.assembly_mode";
    if (!node.IsMap()) {
      return Error(path, "expected a mapping {pose: [x, y, z, q1, q2, q3], min_det_ratio: r}, found " + Describe(node));
    }
    if (Status s = CheckKeys(node, path, kAssemblyModeKeys, {"pose"}); !s.ok()) return s;
    StatusOr<std::vector<double>> pose = Numbers(node["pose"], path + ".pose", 6, "[x, y, z, q1, q2, q3]");
    if (!pose.ok()) return pose.status();
    AssemblyMode mode;
    mode.pose = Eigen::Map<const Vector6d>(pose->data());
    if (node["min_det_ratio"]) {
      StatusOr<double> ratio = Number(node["min_det_ratio"], path + ".min_det_ratio");
      if (!ratio.ok()) return ratio.status();
      if (*ratio < 0 || *ratio >= 1) {
        return Error(path + ".min_det_ratio", "must be in [0, 1), found " + FormatNumber(*ratio));
      }
      mode.min_det_ratio = *ratio;
    }
    *out = mode;
    return Status::Ok();
  }

  // The mode is the side of the singularities its pose is on: a pose on one
  // names no side. Unit-free: rows [u, (R b) x u / radius], |det| <= 8.
  Status CheckAssemblyModePose(const Robot& robot) const {
    if (!robot.limits.assembly_mode) return Status::Ok();
    double radius = 0;
    for (const Leg& leg : robot.legs) radius = std::max(radius, leg.b_in_platform.norm());
    Eigen::Matrix<double, kNumLegs, 6> j =
        InverseKinematicsJacobian(robot, robot.PoseFromVector(robot.limits.assembly_mode->pose));
    j.rightCols<3>() /= radius;
    constexpr double kSingularDet = 1e-9;
    if (!(std::abs(j.determinant()) > kSingularDet)) {
      return Error("limits.assembly_mode.pose", "is at a parallel singularity (det of the inverse-kinematics "
                                                "Jacobian is 0): it names no assembly mode");
    }
    return Status::Ok();
  }

  Status ReadPoseBox(const YAML::Node& node, const std::string& key, std::optional<PoseBox>* out) const {
    if (!node.IsDefined() || node.IsNull()) return Status::Ok();
    const std::string path = "limits." + key;
    if (!node.IsMap()) return Error(path, "expected a mapping, found " + Describe(node));
    if (Status s = CheckKeys(node, path, kPoseBoxKeys, {}); !s.ok()) return s;
    PoseBox box;
    for (size_t k = 0; k < kPoseBoxKeys.size(); ++k) {
      if (!node[kPoseBoxKeys[k]]) continue;
      StatusOr<Range> range = MinMax(node[kPoseBoxKeys[k]], Child(path, kPoseBoxKeys[k]));
      if (!range.ok()) return range.status();
      box.bounds[k] = *range;
    }
    *out = box;
    return Status::Ok();
  }

  std::string label_;
};

std::string YamlList(std::initializer_list<double> values) {
  std::vector<std::string> numbers;
  for (const double v : values) numbers.push_back(FormatNumber(v));
  return "[" + Join(numbers, ", ") + "]";
}

std::string YamlPoint(const Eigen::Vector3d& p) { return YamlList({p.x(), p.y(), p.z()}); }

std::string YamlText(const std::string& text) {
  YAML::Emitter emitter;  // quotes only when plain YAML would read something else
  emitter << text;
  return emitter.c_str();
}

}  // namespace

StatusOr<Robot> ParseRobotYaml(const std::string& text, const std::string& source) {
  return RobotYamlReader("robot file '" + source + "'").Read(text);
}

StatusOr<Robot> LoadRobot(const std::string& path_or_preset) {
  std::error_code error;
  // symlink_status: a dangling link is a file that is meant, not a preset's name.
  if (std::filesystem::exists(std::filesystem::symlink_status(path_or_preset, error))) {
    StatusOr<std::string> text = ReadFileToString(path_or_preset);
    if (!text.ok()) {
      // ReadFileToString starts its messages with the path; say it once.
      const std::string& message = text.status().message();
      const std::string prefix = path_or_preset + ": ";
      const size_t skip = message.rfind(prefix, 0) == 0 ? prefix.size() : 0;
      const std::string reworded = "robot file '" + path_or_preset + "': " + message.substr(skip);
      // A read that failed stays I/O (core/status.h); the rest is the path's fault.
      return text.status().kind() == StatusKind::kIo ? Status::IoError(reworded) : Status::BadInput(reworded);
    }
    return ParseRobotYaml(*text, path_or_preset);
  }
  const auto& presets = EmbeddedPresets();
  if (const auto preset = presets.find(path_or_preset); preset != presets.end()) {
    return RobotYamlReader("robot preset '" + preset->first + "'").Read(preset->second);
  }
  return Status::BadInput("robot '" + path_or_preset +
                          "': no such file and no preset of that name (presets: " + Join(PresetNames(), ", ") + ")");
}

std::string RobotToYaml(const Robot& robot) {
  std::ostringstream out;
  out << "# hexcal robot file; format: docs/robot-file.md\n"
      << "name: " << YamlText(robot.name) << "\n"
      << "length_unit: " << LengthUnitName(robot.length_unit) << "\n"
      << "euler: " << EulerConventionName(robot.euler)
      << (robot.euler == EulerConvention::kXYZ ? "  # R = Rz(q3)*Ry(q2)*Rx(q1)" : "  # R = Rx(q3)*Ry(q2)*Rz(q1)")
      << ", pose angles in degrees\n"
      << "legs:\n";
  for (const Leg& leg : robot.legs) {
    out << "  - {a: " << YamlPoint(leg.a_in_base) << ", b: " << YamlPoint(leg.b_in_platform)
        << ", l: " << FormatNumber(leg.offset) << ", stroke: " << YamlList({leg.stroke_min, leg.stroke_max}) << "}\n";
  }
  const RobotLimits& limits = robot.limits;
  if (!limits.base_joint_max_deg && !limits.platform_joint_max_deg && !limits.leg_min_distance &&
      !limits.assembly_mode && !limits.pose_box && !limits.sampling_box) {
    return out.str();
  }
  out << "limits:\n";
  if (limits.base_joint_max_deg) {
    out << "  base_joint_max_deg: " << FormatNumber(*limits.base_joint_max_deg) << "\n";
  }
  if (limits.platform_joint_max_deg) {
    out << "  platform_joint_max_deg: " << FormatNumber(*limits.platform_joint_max_deg) << "\n";
  }
  if (limits.leg_min_distance) {
    out << "  leg_min_distance: " << FormatNumber(*limits.leg_min_distance) << "\n";
  }
  if (const auto& mode = limits.assembly_mode) {
    const Vector6d& p = mode->pose;
    out << "  assembly_mode: {pose: " << YamlList({p[0], p[1], p[2], p[3], p[4], p[5]})
        << ", min_det_ratio: " << FormatNumber(mode->min_det_ratio) << "}\n";
  }
  for (const auto& [key, box] :
       {std::pair{"pose_box", &limits.pose_box}, std::pair{"sampling_box", &limits.sampling_box}}) {
    if (!*box) continue;
    std::vector<std::string> entries;
    for (size_t k = 0; k < kPoseBoxKeys.size(); ++k) {
      if (const auto& range = (*box)->bounds[k])
        entries.push_back(kPoseBoxKeys[k] + ": " + YamlList({range->min, range->max}));
    }
    out << "  " << key << ": {" << Join(entries, ", ") << "}\n";
  }
  return out.str();
}

Status SaveRobot(const Robot& robot, const std::string& path) { return WriteFileAtomically(path, RobotToYaml(robot)); }

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const auto& entry : EmbeddedPresets()) names.push_back(entry.first);
  return names;
}

}  // namespace hexcal

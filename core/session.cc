#include "core/session.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/noise_yaml.h"
#include "core/tracker_yaml.h"
#include "core/yaml_document.h"

namespace hexcal {

namespace fs = std::filesystem;

const char* InstrumentName(Instrument instrument) {
  return instrument == Instrument::kPoints ? "points" : "camera";
}

const char* MeasurementNoun(Instrument instrument) { return instrument == Instrument::kPoints ? "pose" : "image"; }

bool SessionConfig::IsValid(std::string* error) const {
  if (robot.empty()) {
    *error = "session: no robot";
    return false;
  }
  if (instrument == Instrument::kPoints) {
    if (points.empty()) {
      *error = "session: a points session needs its points file (points:)";
      return false;
    }
    if (!(point_sigma > 0 && point_sigma < 1e6)) {
      *error = "session: point_sigma must be a positive length in the robot's unit";
      return false;
    }
    if (tracker && !tracker->IsValid(error)) return false;
    return noise.IsValid(error);
  }
  if (tracker) {
    *error = "session: tracker: only a points session has a tracker";
    return false;
  }
  if (camera.empty()) {
    *error = "session: no camera";
    return false;
  }
  if (target.empty()) {
    *error = "session: no target";
    return false;
  }
  return noise.IsValid(error);
}

SessionPaths::SessionPaths(std::string folder)
    : dir(std::move(folder)),
      config((fs::path(dir) / "session.yaml").string()),
      plan((fs::path(dir) / "plan.csv").string()),
      images((fs::path(dir) / "images").string()),
      legs((fs::path(dir) / "legs.csv").string()),
      camera_poses((fs::path(dir) / "camera_poses.csv").string()),
      results((fs::path(dir) / "results").string()),
      noise_check((fs::path(dir) / kNoiseCheckFile).string()) {}

namespace {

// A frame as [x, y, z, q1, q2, q3] with the xyz Euler convention, degrees.
YAML::Node FrameNode(const Pose& pose) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.SetStyle(YAML::EmitterStyle::Flow);
  const Vector6d v = VectorFromPose(pose, EulerConvention::kXYZ);
  for (int k = 0; k < 6; ++k) node.push_back(FormatNumber(v[k]));
  return node;
}

StatusOr<Pose> ParseFrame(const YAML::Node& frames, const std::string& source, const std::string& key) {
  // frames[key] of a mapping without the key is an invalid node that throws on
  // every query but IsDefined (found by fuzz/session_fuzz).
  const YAML::Node node = frames[key];
  if (!node.IsDefined()) return Status::BadInput(source + ": frames." + key + ": missing");
  if (!node.IsSequence() || node.size() != 6)
    return Status::BadInput(source + ": frames." + key + " must be [x, y, z, q1, q2, q3]");
  Vector6d v;
  for (int k = 0; k < 6; ++k) {
    try {
      v[k] = node[k].as<double>();
    } catch (const YAML::Exception&) {
      return Status::BadInput(source + ": frames." + key + " entry " + std::to_string(k + 1) + " is not a number");
    }
    if (!std::isfinite(v[k])) return Status::BadInput(source + ": frames." + key + " is not finite");
  }
  return PoseFromVector(v, EulerConvention::kXYZ);
}

std::string ConfigText(const SessionConfig& config) {
  YAML::Emitter out;
  out << YAML::Comment("hexcal session (docs/session.md)");
  YAML::Node root;
  root["robot"] = config.robot;
  if (config.instrument == Instrument::kPoints) {
    root["instrument"] = InstrumentName(config.instrument);
    root["points"] = config.points;
    if (!config.reflectors.empty()) root["reflectors"] = config.reflectors;
    root["point_sigma"] = FormatNumber(config.point_sigma);
    if (config.tracker) root["tracker"] = TrackerSectionNode(*config.tracker);
  } else {  // the camera session's file as it always was
    root["camera"] = config.camera;
    root["target"] = config.target;
  }
  YAML::Node noise;  // each key of NoiseModelOptions(), shortest exact form, unquoted
  for (const OptionSpec<NoiseModel>& spec : NoiseModelOptions()) noise[spec.key] = OptionText(spec, config.noise);
  root["noise"] = noise;
  if (config.base_from_camera && config.platform_from_target) {
    YAML::Node frames;
    frames["base_from_camera"] = FrameNode(*config.base_from_camera);
    frames["platform_from_target"] = FrameNode(*config.platform_from_target);
    root["frames"] = frames;
  }
  out << root;
  return std::string(out.c_str()) + "\n";
}

std::set<std::string> ImageFiles(const std::string& folder) {
  std::set<std::string> names;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff")
      names.insert(entry.path().filename().string());
  }
  return names;
}

// The keys naming the robot and the instrument's files: robot, camera and
// target, or for a points session instrument, points, reflectors, point_sigma.
Status ReadInstrument(const YAML::Node& root, const std::string& source, SessionConfig* config) {
  const auto text = [&](const char* key, std::string* value) {
    if (!root[key] || !root[key].IsScalar()) return Status::BadInput(source + ": missing '" + key + "'");
    *value = root[key].as<std::string>();
    return Status::Ok();
  };
  if (Status s = text("robot", &config->robot); !s.ok()) return s;
  std::string instrument = "camera";
  if (root["instrument"] && !text("instrument", &instrument).ok())
    return Status::BadInput(source + ": instrument: expected camera or points");
  if (instrument == "camera") {
    if (Status s = text("camera", &config->camera); !s.ok()) return s;
    return text("target", &config->target);
  }
  if (instrument != "points")
    return Status::BadInput(source + ": instrument: '" + instrument + "' is not camera or points");
  config->instrument = Instrument::kPoints;
  if (Status s = text("points", &config->points); !s.ok()) return s;
  if (root["reflectors"] && !text("reflectors", &config->reflectors).ok())
    return Status::BadInput(source + ": reflectors: expected a file name");
  std::string sigma;
  if (Status s = text("point_sigma", &sigma); !s.ok()) return s;
  StatusOr<double> value = ParseNumber(sigma);
  if (!value.ok() || !(*value > 0 && *value < 1e6))
    return Status::BadInput(source + ": point_sigma: expected a positive length in the robot's unit");
  config->point_sigma = *value;
  return Status::Ok();
}

}  // namespace

StatusOr<std::optional<Vector6d>> CommandedPoseAt(const CsvTable& table, size_t row, const std::array<int, 6>& columns,
                                                  const std::string& where) {
  int empty = 0;
  for (int k = 0; k < 6; ++k) empty += table.rows[row][columns[k]].empty();
  if (empty == 6) return std::optional<Vector6d>();
  if (empty != 0)
    return Status::BadInput(where + "the commanded pose has " + std::to_string(6 - empty) +
                            " of its six cells; fill all six or none");
  Vector6d pose;
  for (int k = 0; k < 6; ++k) {
    StatusOr<double> value = NumberAt(table, row, columns[k]);
    if (!value.ok()) return value.status();
    pose[k] = *value;
  }
  return std::optional<Vector6d>(pose);
}

Status SaveSessionConfig(const std::string& dir, const SessionConfig& config) {
  std::string error;
  if (!config.IsValid(&error)) return Status::BadInput(error);
  return WriteFileAtomically(SessionPaths(dir).config, ConfigText(config));
}

Status InitSession(const std::string& dir, const SessionConfig& config) {
  const SessionPaths paths(dir);
  std::string error;
  if (!config.IsValid(&error)) return Status::BadInput(error);
  std::error_code fs_error;
  if (fs::exists(paths.config, fs_error))
    return Status::BadInput(paths.config + ": exists; a session is never initialised twice");
  for (const std::string& folder : {paths.dir, paths.images, paths.results})
    if (Status s = CreateFolders(folder); !s.ok()) return s;
  return SaveSessionConfig(dir, config);
}

StatusOr<SessionConfig> LoadSessionConfig(const std::string& dir) {
  const SessionPaths paths(dir);
  StatusOr<std::string> text = ReadFileToString(paths.config);
  if (!text.ok()) return text.status();
  const StatusOr<YAML::Node> document = LoadYamlDocument(*text, paths.config);
  if (!document.ok()) return document.status();
  const YAML::Node& root = *document;
  if (!root.IsMap()) return Status::BadInput(paths.config + ": not a YAML mapping");
  SessionConfig config;
  try {
    if (Status s = ReadInstrument(root, paths.config, &config); !s.ok()) return s;
    if (const YAML::Node noise = root["noise"]) {
      StatusOr<NoiseModel> read = ReadNoiseSection(noise, paths.config + ": noise");
      if (!read.ok()) return read.status();
      config.noise = *read;
    }
    if (const YAML::Node tracker = root["tracker"]) {
      StatusOr<TrackerSettings> read = ReadTrackerSection(tracker, paths.config);
      if (!read.ok()) return read.status();
      config.tracker = *read;
    }
  } catch (const YAML::Exception& e) {
    return Status::BadInput(paths.config + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (const YAML::Node frames = root["frames"]) {
    if (!frames.IsMap())
      return Status::BadInput(paths.config + ": frames: expected base_from_camera and platform_from_target");
    StatusOr<Pose> x = ParseFrame(frames, paths.config, "base_from_camera");
    if (!x.ok()) return x.status();
    StatusOr<Pose> y = ParseFrame(frames, paths.config, "platform_from_target");
    if (!y.ok()) return y.status();
    config.base_from_camera = *x;
    config.platform_from_target = *y;
  }
  std::string error;
  if (!config.IsValid(&error)) return Status::BadInput(paths.config + ": " + error);
  return config;
}

// What to do about readings that are missing, said the same in every message.
constexpr const char* kEnterReadings =
    "enter the six leg readings of each image (the GUI's readings table, `hexcal session record`, or a CSV "
    "image,L1..L6 imported)";

StatusOr<std::vector<LegsRow>> LoadSessionLegs(const std::string& dir) {
  const SessionPaths paths(dir);
  std::error_code missing;
  if (!fs::exists(fs::symlink_status(paths.legs, missing)))
    return Status::BadInput(paths.legs + ": no readings yet: " + kEnterReadings);
  StatusOr<CsvTable> table = ReadCsv(paths.legs);
  if (!table.ok()) return table.status();
  // A session.yaml that does not load is reported by whoever loads it; the
  // rows are then read as a camera session's.
  const StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  const bool points = config.ok() && config->instrument == Instrument::kPoints;
  const char* key = MeasurementNoun(points ? Instrument::kPoints : Instrument::kCamera);
  StatusOr<int> image_column = ColumnIndex(*table, key);
  if (!image_column.ok()) return image_column.status();
  int leg_columns[kNumLegs];
  for (int i = 0; i < kNumLegs; ++i) {
    StatusOr<int> column = ColumnIndex(*table, "L" + std::to_string(i + 1));
    if (!column.ok()) return column.status();
    leg_columns[i] = *column;
  }
  const auto holdout_it = std::find(table->header.begin(), table->header.end(), "holdout");
  const int holdout_column = holdout_it == table->header.end() ? -1 : int(holdout_it - table->header.begin());
  std::array<int, 6> commanded_columns{};
  int commanded_found = 0;
  for (int k = 0; k < 6; ++k) {
    const auto it = std::find(table->header.begin(), table->header.end(), kCommandedColumns[k]);
    commanded_columns[k] = it == table->header.end() ? -1 : int(it - table->header.begin());
    commanded_found += commanded_columns[k] >= 0;
  }
  if (commanded_found != 0 && commanded_found != 6)
    return Status::BadInput(paths.legs + ": has " + std::to_string(commanded_found) +
                            " of the six commanded_x..commanded_q3 columns; it needs all six or none");

  const std::set<std::string> images = ImageFiles(paths.images);
  std::set<std::string> seen;
  std::vector<LegsRow> rows;
  for (size_t r = 0; r < table->rows.size(); ++r) {
    LegsRow row;
    row.line = table->line_numbers[r];
    const std::string where = paths.legs + ":" + std::to_string(row.line) + ": ";
    row.image = table->rows[r][*image_column];
    if (!points && images.count(row.image) == 0)
      return Status::BadInput(where + "image '" + row.image + "' is not in images/");
    if (row.image.empty()) return Status::BadInput(where + "column '" + key + "' is empty");
    if (!seen.insert(row.image).second) return Status::BadInput(where + key + " '" + row.image + "' has a second row");
    for (int i = 0; i < kNumLegs; ++i) {
      StatusOr<double> value = NumberAt(*table, r, leg_columns[i]);
      if (!value.ok()) return value.status();
      row.legs[i] = *value;
    }
    if (holdout_column >= 0) {
      const std::string& cell = table->rows[r][holdout_column];
      if (cell != "0" && cell != "1") return Status::BadInput(where + "column 'holdout': '" + cell + "' is not 0 or 1");
      row.holdout = cell == "1";
    }
    if (commanded_found == 6) {
      StatusOr<std::optional<Vector6d>> commanded = CommandedPoseAt(*table, r, commanded_columns, where);
      if (!commanded.ok()) return commanded.status();
      row.commanded = *commanded;
    }
    rows.push_back(row);
  }
  for (const std::string& image : images) {
    if (!points && seen.count(image) == 0)
      return Status::BadInput((fs::path(paths.images) / image).string() + ": no row in " + paths.legs + ": " +
                              kEnterReadings);
  }
  return rows;
}

}  // namespace hexcal

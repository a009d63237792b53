// Camera files in (camera.h): OpenCV FileStorage YAML and XML, ROS camera_info
// YAML and Kalibr camchain YAML. Out: camera_writers.cc.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/yaml_document.h"
#include "vision/camera.h"

namespace hexcal {
namespace {

// node[key] when node is a mapping, else a null node (never throws).
YAML::Node MapChild(const YAML::Node& node, const char* key) {
  if (!node || !node.IsMap()) return YAML::Node();
  return node[key];
}

// The `distortion_model` names of ROS (plumb_bob, rational_polynomial,
// equidistant), Kalibr (radtan, equidistant) and hexcal (fisheye too).
std::optional<CameraModel> ModelFromDistortionName(const std::string& name) {
  if (name == "plumb_bob" || name == "radtan") return CameraModel::kRadTan;
  if (name == "rational_polynomial" || name == "rational") return CameraModel::kRational;
  if (name == "equidistant" || name == "fisheye" || name == "pinhole-equi") return CameraModel::kPinholeEqui;
  return std::nullopt;
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

class CameraReader {
 public:
  explicit CameraReader(const std::string& source) : label_("camera file '" + source + "'") {}

  Status Error(const std::string& problem) const { return Status::BadInput(label_ + ": " + problem); }

  // `model`: the file's distortion_model, or nullopt: 4 or 5 coefficients are
  // kRadTan, more (8, 12, 14: OpenCV's lists) kRational. Coefficients past the
  // model's must be 0. `d_key` names the list in errors.
  StatusOr<Camera> FromArrays(int width, int height, const std::vector<double>& k, const std::vector<double>& d,
                              std::optional<CameraModel> model, const std::string& d_key) const {
    if (k.size() != 9) return Error("camera_matrix: expected 9 numbers (3 x 3), found " + std::to_string(k.size()));
    if (k[1] != 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1) {
      return Error("camera_matrix: expected [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
    }
    Camera camera;
    camera.model = model ? *model : d.size() <= 5 ? CameraModel::kRadTan : CameraModel::kRational;
    const size_t wanted = static_cast<size_t>(camera.NumCoefficients());
    const std::vector<std::string> parameters = camera.ParameterNames();
    const std::string names = Join(std::vector<std::string>(parameters.begin() + 4, parameters.end()));
    if (d.size() < 4) {
      return Error(d_key + ": expected " + names + " (" + CameraModelName(camera.model) + "), found " +
                   std::to_string(d.size()) + " numbers");
    }
    for (size_t i = wanted; i < d.size(); ++i) {
      if (d[i] != 0) {
        return Error(d_key + ": coefficient " + std::to_string(i + 1) + " is not 0; the " +
                     CameraModelName(camera.model) + " model has " + names);
      }
    }
    camera.width = width;
    camera.height = height;
    camera.fx = k[0];
    camera.cx = k[2];
    camera.fy = k[4];
    camera.cy = k[5];
    for (size_t i = 0; i < wanted && i < d.size(); ++i) camera.distortion[i] = d[i];
    return Finish(camera);
  }

  // The numbers of an !!opencv-matrix, read entry by entry: OpenCV's own
  // `node >> cv::Mat` trusts rows and cols and allocates what a corrupt file
  // claims (tens of GB, found by fuzz/camera_fuzz).
  StatusOr<std::vector<double>> OpenCvMatrix(const cv::FileNode& node, const std::string& key) const {
    if (node.empty()) return Error(key + ": missing");
    if (!node.isMap()) return Error(key + ": expected an !!opencv-matrix (rows, cols, dt, data)");
    const cv::FileNode rows = node["rows"], cols = node["cols"], data = node["data"];
    if (!rows.isInt() || !cols.isInt()) return Error(key + ": rows, cols: missing or not whole numbers");
    const int r = static_cast<int>(rows), c = static_cast<int>(cols);
    constexpr int kMaxEntries = 64;  // a 3 x 3 matrix or a handful of coefficients
    if (r < 1 || c < 1 || r > kMaxEntries || c > kMaxEntries || r * c > kMaxEntries) {
      return Error(key + ": " + std::to_string(r) + " x " + std::to_string(c) +
                   " is not a camera matrix or coefficient list");
    }
    if (!data.isSeq() || static_cast<int>(data.size()) != r * c) {
      return Error(key + ".data: expected " + std::to_string(r * c) + " numbers (" + std::to_string(r) + " x " +
                   std::to_string(c) + ")");
    }
    std::vector<double> values;
    for (const cv::FileNode& item : data) {
      if (!item.isReal() && !item.isInt()) {
        return Error(key + ".data: entry " + std::to_string(values.size() + 1) + " is not a number");
      }
      const double value = static_cast<double>(item);
      if (!std::isfinite(value)) {
        return Error(key + ".data: entry " + std::to_string(values.size() + 1) + " (" + std::to_string(value) +
                     ") is not a finite number");
      }
      values.push_back(value);
    }
    return values;
  }

  StatusOr<Camera> ReadOpenCv(const std::string& text) const {
    try {
      cv::FileStorage storage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
      if (!storage.isOpened()) return Error("not an OpenCV FileStorage file");
      StatusOr<std::vector<double>> k = OpenCvMatrix(storage["camera_matrix"], "camera_matrix");
      if (!k.ok()) return k.status();
      StatusOr<std::vector<double>> d = OpenCvMatrix(storage["distortion_coefficients"], "distortion_coefficients");
      if (!d.ok()) return d.status();
      const cv::FileNode w = storage["image_width"], h = storage["image_height"];
      if (!w.isInt() || !h.isInt()) return Error("image_width, image_height: missing or not whole numbers");
      std::optional<CameraModel> model;
      if (const cv::FileNode name = storage["distortion_model"]; !name.empty()) {
        StatusOr<CameraModel> named = Model(name.isString() ? name.string() : std::string(), name.isString());
        if (!named.ok()) return named.status();
        model = *named;
      }
      return FromArrays(static_cast<int>(w), static_cast<int>(h), *k, *d, model, "distortion_coefficients");
    } catch (const cv::Exception& e) {
      return Error(std::string("cannot read as OpenCV FileStorage: ") + e.msg);
    } catch (const std::exception& e) {
      // OpenCV 4.6's parser also lets standard exceptions out on some broken
      // files (std::length_error, found by fuzz/camera_fuzz).
      return Error(std::string("cannot read as OpenCV FileStorage: malformed file (") + e.what() + ")");
    }
  }

  // ROS camera_info (camera_calibration_parsers' layout or the CameraInfo
  // message's), hexcal's OpenCV layout, or a Kalibr camchain.
  StatusOr<Camera> ReadYaml(const std::string& text) const {
    const StatusOr<YAML::Node> document = LoadYamlDocument(text, label_);
    if (!document.ok()) return document.status();
    const YAML::Node& root = *document;
    if (!root.IsMap()) return Error("expected a camera mapping (OpenCV, ROS camera_info or Kalibr camchain)");
    return WithYamlBackstop<Camera>(label_, [&]() -> StatusOr<Camera> {
      if (root["cam0"]) return ReadKalibr(root["cam0"], "cam0");
      if (root["camera_model"] || root["intrinsics"]) return ReadKalibr(root, "");
      // A camchain of cam1 only read as ROS said "image_width: missing" (issue 36).
      if (root["cam1"]) return Error("cam1: a Kalibr camchain without cam0; hexcal reads cam0");
      return ReadRos(root);
    });
  }

 private:
  StatusOr<Camera> Finish(Camera camera) const {
    if (Status s = camera.Validate(); !s.ok()) return Error(s.message());
    return camera;
  }

  StatusOr<CameraModel> Model(const std::string& name, bool is_text,
                              const std::string& key = "distortion_model") const {
    const std::optional<CameraModel> model = is_text ? ModelFromDistortionName(name) : std::nullopt;
    if (model) return *model;
    return Error(key + ": " + (is_text ? Excerpt(name) : std::string("not a name")) +
                 " is not supported; expected plumb_bob, rational_polynomial or equidistant");
  }

  StatusOr<std::vector<double>> Numbers(const YAML::Node& node, const std::string& key) const {
    if (!node || !node.IsSequence()) return Error(key + ": expected a list of numbers");
    std::vector<double> values;
    for (const YAML::Node& item : node) {
      StatusOr<double> value = item.IsScalar() ? ParseNumber(item.Scalar()) : Status::BadInput("");
      if (!value.ok())
        return Error(key + ": expected numbers, found " + (item.IsScalar() ? Excerpt(item.Scalar()) : "a list"));
      values.push_back(*value);
    }
    return values;
  }

  // The numbers of `{rows, cols, data}` (OpenCV's !!opencv-matrix, ROS's
  // camera_calibration_parsers): rows and cols, when given, must be a small
  // matrix that `data` fills exactly.
  StatusOr<std::vector<double>> MatrixData(const YAML::Node& node, const std::string& key) const {
    StatusOr<std::vector<double>> data = Numbers(MapChild(node, "data"), key + ".data");
    if (!data.ok() || !MapChild(node, "rows") || !MapChild(node, "cols")) return data;
    const YAML::Node rows_node = node["rows"], cols_node = node["cols"];
    StatusOr<double> rows = rows_node.IsScalar() ? ParseNumber(rows_node.Scalar()) : Status::BadInput("");
    StatusOr<double> cols = cols_node.IsScalar() ? ParseNumber(cols_node.Scalar()) : Status::BadInput("");
    if (!rows.ok() || !cols.ok() || *rows != std::floor(*rows) || *cols != std::floor(*cols))
      return Error(key + ": rows, cols: missing or not whole numbers");
    constexpr double kMaxEntries = 64;  // a 3 x 3 matrix or a handful of coefficients
    const std::string shape = FormatNumber(*rows) + " x " + FormatNumber(*cols);
    if (*rows < 1 || *cols < 1 || *rows * *cols > kMaxEntries)
      return Error(key + ": " + shape + " is not a camera matrix or coefficient list");
    if (static_cast<double>(data->size()) != *rows * *cols) {
      return Error(key + ".data: expected " + FormatNumber(*rows * *cols) + " numbers (" + shape + "), found " +
                   std::to_string(data->size()));
    }
    return data;
  }

  StatusOr<int> WholeNumber(const YAML::Node& node, const std::string& key) const {
    if (!node || !node.IsScalar()) return Error(key + ": missing");
    StatusOr<double> value = ParseNumber(node.Scalar());
    if (!value.ok() || *value != std::floor(*value) || std::abs(*value) > 1e6) {
      return Error(key + ": expected a whole number, found " + Excerpt(node.Scalar()));
    }
    return static_cast<int>(*value);
  }

  // camera_calibration_parsers' layout (camera_matrix: {rows, cols, data}), or
  // the CameraInfo message's (width, height, K, D).
  StatusOr<Camera> ReadRos(const YAML::Node& map) const {
    const bool message_form = static_cast<bool>(map["K"]);
    std::optional<CameraModel> model;
    if (const YAML::Node node = map["distortion_model"]) {
      StatusOr<CameraModel> named = Model(node.IsScalar() ? node.Scalar() : std::string(), node.IsScalar());
      if (!named.ok()) return named.status();
      model = *named;
    }
    const std::string width_key = message_form ? "width" : "image_width";
    const std::string height_key = message_form ? "height" : "image_height";
    StatusOr<int> width = WholeNumber(map[width_key], width_key);
    if (!width.ok()) return width.status();
    StatusOr<int> height = WholeNumber(map[height_key], height_key);
    if (!height.ok()) return height.status();
    StatusOr<std::vector<double>> k =
        message_form ? Numbers(map["K"], "K") : MatrixData(map["camera_matrix"], "camera_matrix");
    if (!k.ok()) return k.status();
    const std::string d_key = message_form ? "D" : "distortion_coefficients";
    StatusOr<std::vector<double>> d = message_form ? Numbers(map["D"], d_key) : MatrixData(map[d_key], d_key);
    if (!d.ok()) return d.status();
    return FromArrays(*width, *height, *k, *d, model, d_key);
  }

  // Kalibr's camchain entry: camera_model pinhole, intrinsics [fu, fv, pu, pv],
  // distortion_model radtan (k1 k2 r1 r2) | equidistant (k1 k2 k3 k4) | none,
  // distortion_coeffs, resolution [w, h]. `name`: "cam0", or "" for a camera
  // at the top level.
  StatusOr<Camera> ReadKalibr(const YAML::Node& cam, const std::string& name) const {
    const std::string prefix = name.empty() ? "" : name + ".";
    if (!cam.IsMap()) return Error(name + ": expected a Kalibr camera (camera_model, intrinsics, ...)");
    const YAML::Node camera_model = cam["camera_model"];
    if (!camera_model || !camera_model.IsScalar()) return Error(prefix + "camera_model: missing");
    if (camera_model.Scalar() != "pinhole") {
      return Error(prefix + "camera_model: " + Excerpt(camera_model.Scalar()) + " is not supported; expected pinhole");
    }
    StatusOr<std::vector<double>> intrinsics = Numbers(cam["intrinsics"], prefix + "intrinsics");
    if (!intrinsics.ok()) return intrinsics.status();
    if (intrinsics->size() != 4) {
      return Error(prefix + "intrinsics: expected 4 numbers (fu, fv, pu, pv), found " +
                   std::to_string(intrinsics->size()));
    }
    const YAML::Node model_node = cam["distortion_model"];
    if (!model_node || !model_node.IsScalar()) return Error(prefix + "distortion_model: missing");
    const std::string model_name = model_node.Scalar();
    std::vector<double> d;
    if (model_name != "none" || cam["distortion_coeffs"]) {
      StatusOr<std::vector<double>> coeffs = Numbers(cam["distortion_coeffs"], prefix + "distortion_coeffs");
      if (!coeffs.ok()) return coeffs.status();
      d = *coeffs;
    }
    CameraModel model = CameraModel::kRadTan;
    if (model_name == "equidistant") {
      model = CameraModel::kPinholeEqui;
    } else if (model_name != "radtan" && model_name != "none") {
      return Error(prefix + "distortion_model: " + Excerpt(model_name) +
                   " is not supported; expected radtan, equidistant or none");
    }
    const size_t wanted = model_name == "none" ? 0 : 4;
    if (d.size() != wanted &&
        !(model_name == "none" && std::all_of(d.begin(), d.end(), [](double v) { return v == 0; }))) {
      return Error(prefix + "distortion_coeffs: expected " + std::to_string(wanted) + " numbers for " +
                   Excerpt(model_name) + ", found " + std::to_string(d.size()));
    }
    d.resize(4, 0.0);  // radtan: k1 k2 p1 p2, k3 = 0
    StatusOr<std::vector<double>> resolution = Numbers(cam["resolution"], prefix + "resolution");
    if (!resolution.ok()) return resolution.status();
    if (resolution->size() != 2 || std::any_of(resolution->begin(), resolution->end(),
                                               [](double v) { return v != std::floor(v) || std::abs(v) > 1e6; })) {
      return Error(prefix + "resolution: expected 2 whole numbers (width, height)");
    }
    const std::vector<double>& f = *intrinsics;
    return FromArrays(static_cast<int>((*resolution)[0]), static_cast<int>((*resolution)[1]),
                      {f[0], 0, f[2], 0, f[1], f[3], 0, 0, 1}, d, model, prefix + "distortion_coeffs");
  }

  std::string label_;
};

}  // namespace

StatusOr<Camera> ParseCameraFile(const std::string& text, const std::string& source) {
  const CameraReader reader(source);
  const size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string::npos) return reader.Error("empty file");
  if (text.compare(start, 5, "<?xml") == 0) return reader.ReadOpenCv(text);
  if (text.compare(start, 7, "%YAML:1") == 0) {
    // OpenCV's YAML parser loops for ever on some broken files (OpenCV 4.6,
    // found by fuzz/camera_fuzz), so OpenCV's YAML layout is read with
    // yaml-cpp, like the ROS one it matches. "%YAML:1.0" is not a YAML 1.2
    // directive: it becomes a comment, which keeps the line numbers.
    std::string yaml = text;
    yaml[start] = '#';
    return reader.ReadYaml(yaml);
  }
  return reader.ReadYaml(text);
}

StatusOr<Camera> LoadCamera(const std::string& path_or_name) {
  std::error_code error;
  if (path_or_name == kSimulatedCameraName && !std::filesystem::exists(path_or_name, error)) return SimulatedCamera();
  StatusOr<std::string> text = ReadFileToString(path_or_name);
  if (!text.ok()) {
    return text.status().WithHint(" (a camera file, or the built-in name " + std::string(kSimulatedCameraName) + ")");
  }
  return ParseCameraFile(*text, path_or_name);
}

}  // namespace hexcal

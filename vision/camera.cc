#include "vision/camera.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <limits>
#include <locale>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/yaml_document.h"

namespace hexcal {
namespace {

// d(x_d, y_d)/d(x, y) of the distortion model in camera.h.
Eigen::Matrix2d DistortionJacobian(const Camera& camera, const Eigen::Vector2d& xy) {
  const auto& [k1, k2, p1, p2, k3] = camera.distortion;
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double radial_d = k1 + r2 * (2 * k2 + 3 * k3 * r2);  // d radial / d r²
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2 * x * x * radial_d + 2 * p1 * y + 6 * p2 * x;
  j(0, 1) = 2 * x * y * radial_d + 2 * p1 * x + 2 * p2 * y;
  j(1, 0) = 2 * x * y * radial_d + 2 * p1 * x + 2 * p2 * y;
  j(1, 1) = radial + 2 * y * y * radial_d + 6 * p1 * y + 2 * p2 * x;
  return j;
}

// node[key] when node is a mapping, else a null node (never throws).
YAML::Node MapChild(const YAML::Node& node, const char* key) {
  if (!node || !node.IsMap()) return YAML::Node();
  return node[key];
}

std::string Matrix(const std::string& name, int rows, int cols, const std::vector<double>& data) {
  std::string text = name + ": !!opencv-matrix\n   rows: " + std::to_string(rows) +
                     "\n   cols: " + std::to_string(cols) + "\n   dt: d\n   data: [ ";
  for (size_t i = 0; i < data.size(); ++i) text += (i ? ", " : "") + FormatNumber(data[i]);
  return text + " ]\n";
}

class CameraReader {
 public:
  explicit CameraReader(const std::string& source) : label_("camera file '" + source + "'") {}

  Status Error(const std::string& problem) const { return Status::Error(label_ + ": " + problem); }

  StatusOr<Camera> Finish(Camera camera) const {
    if (Status s = camera.Validate(); !s.ok()) return Error(s.message());
    return camera;
  }

  // K row-major 3×3 and 4, 5 or more coefficients (the ones past k3 must be 0).
  StatusOr<Camera> FromArrays(int width, int height, const std::vector<double>& k, const std::vector<double>& d) const {
    if (k.size() != 9) return Error("camera_matrix: expected 9 numbers (3 x 3), found " + std::to_string(k.size()));
    if (k[1] != 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1) {
      return Error("camera_matrix: expected [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
    }
    if (d.size() < 4) {
      return Error("distortion_coefficients: expected k1, k2, p1, p2[, k3], found " + std::to_string(d.size()) +
                   " numbers");
    }
    for (size_t i = 5; i < d.size(); ++i) {
      if (d[i] != 0) {
        return Error("distortion_coefficients: coefficient " + std::to_string(i + 1) +
                     " is not 0; only k1, k2, p1, p2, k3 (plumb bob) are supported");
      }
    }
    Camera camera;
    camera.width = width;
    camera.height = height;
    camera.fx = k[0];
    camera.cx = k[2];
    camera.fy = k[4];
    camera.cy = k[5];
    for (size_t i = 0; i < 5 && i < d.size(); ++i) camera.distortion[i] = d[i];
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
      return FromArrays(static_cast<int>(w), static_cast<int>(h), *k, *d);
    } catch (const cv::Exception& e) {
      return Error(std::string("cannot read as OpenCV FileStorage: ") + e.msg);
    } catch (const std::exception& e) {
      // OpenCV 4.6's parser also lets standard exceptions out on some broken
      // files (std::length_error, found by fuzz/camera_fuzz).
      return Error(std::string("cannot read as OpenCV FileStorage: malformed file (") + e.what() + ")");
    }
  }

  StatusOr<std::vector<double>> Numbers(const YAML::Node& node, const std::string& key) const {
    if (!node || !node.IsSequence()) return Error(key + ": expected a list of numbers");
    std::vector<double> values;
    for (const YAML::Node& item : node) {
      StatusOr<double> value = item.IsScalar() ? ParseNumber(item.Scalar()) : Status::Error("");
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
    StatusOr<double> rows = rows_node.IsScalar() ? ParseNumber(rows_node.Scalar()) : Status::Error("");
    StatusOr<double> cols = cols_node.IsScalar() ? ParseNumber(cols_node.Scalar()) : Status::Error("");
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

  StatusOr<int> Int(const YAML::Node& root, const std::string& key) const {
    const YAML::Node node = root[key];
    if (!node || !node.IsScalar()) return Error(key + ": missing");
    StatusOr<double> value = ParseNumber(node.Scalar());
    if (!value.ok() || *value != std::floor(*value) || std::abs(*value) > 1e6) {
      return Error(key + ": expected a whole number, found " + Excerpt(node.Scalar()));
    }
    return static_cast<int>(*value);
  }

  // camera_calibration_parsers' layout (camera_matrix: {rows, cols, data}), or
  // the CameraInfo message's (width, height, K, D).
  StatusOr<Camera> ReadRos(const std::string& text) const {
    const StatusOr<YAML::Node> document = LoadYamlDocument(text, label_);
    if (!document.ok()) return document.status();
    const YAML::Node& root = *document;
    if (!root.IsMap()) return Error("expected a ROS camera_info mapping or an OpenCV FileStorage file");
    const YAML::Node& map = root;
    return WithYamlBackstop<Camera>(label_, [&]() -> StatusOr<Camera> {
      const bool message_form = static_cast<bool>(map["K"]);
      const YAML::Node model_node = map["distortion_model"];
      if (model_node && model_node.IsScalar()) {
        const std::string model = model_node.Scalar();
        if (model != "plumb_bob" && model != "rational_polynomial") {
          return Error("distortion_model: " + Excerpt(model) + " is not supported; expected plumb_bob");
        }
      }
      StatusOr<int> width = Int(map, message_form ? "width" : "image_width");
      if (!width.ok()) return width.status();
      StatusOr<int> height = Int(map, message_form ? "height" : "image_height");
      if (!height.ok()) return height.status();
      StatusOr<std::vector<double>> k =
          message_form ? Numbers(map["K"], "K") : MatrixData(map["camera_matrix"], "camera_matrix");
      if (!k.ok()) return k.status();
      StatusOr<std::vector<double>> d =
          message_form ? Numbers(map["D"], "D") : MatrixData(map["distortion_coefficients"], "distortion_coefficients");
      if (!d.ok()) return d.status();
      return FromArrays(*width, *height, *k, *d);
    });
  }

 private:
  std::string label_;
};

}  // namespace

cv::Mat Camera::DistortionCoefficients() const {
  cv::Mat d(1, 5, CV_64F);
  for (int i = 0; i < 5; ++i) d.at<double>(0, i) = distortion[static_cast<size_t>(i)];
  return d;
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& xy) const {
  const auto& [k1, k2, p1, p2, k3] = distortion;
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

Eigen::Vector2d Camera::Project(const Eigen::Vector3d& p_in_camera) const {
  const Eigen::Vector2d d = Distort(p_in_camera.head<2>() / p_in_camera.z());
  return {fx * d.x() + cx, fy * d.y() + cy};
}

std::optional<Eigen::Vector2d> Camera::Undistort(const Eigen::Vector2d& pixel, const Eigen::Vector2d* start) const {
  const Eigen::Vector2d target((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  Eigen::Vector2d xy = start ? *start : target;
  double error = (Distort(xy) - target).norm();
  for (int iteration = 0; iteration < 50 && error > 1e-13; ++iteration) {
    const Eigen::Matrix2d j = DistortionJacobian(*this, xy);
    if (!(j.determinant() > 0)) return std::nullopt;
    const Eigen::Vector2d step = j.inverse() * (target - Distort(xy));
    // Damped: halve the step until the residual drops.
    double scale = 1;
    Eigen::Vector2d next = xy + step;
    double next_error = (Distort(next) - target).norm();
    while (next_error >= error && scale > 1e-6) {
      scale *= 0.5;
      next = xy + scale * step;
      next_error = (Distort(next) - target).norm();
    }
    if (next_error >= error) break;
    xy = next;
    error = next_error;
  }
  if (!(error <= 1e-11) || !(DistortionJacobian(*this, xy).determinant() > 0)) return std::nullopt;
  return xy;
}

std::optional<Eigen::Vector2d> Camera::IdealPixel(const Eigen::Vector2d& pixel) const {
  const std::optional<Eigen::Vector2d> xy = Undistort(pixel);
  if (!xy) return std::nullopt;
  return Eigen::Vector2d(fx * xy->x() + cx, fy * xy->y() + cy);
}

Eigen::Vector2d Camera::DistortedPixel(const Eigen::Vector2d& ideal_pixel) const {
  const Eigen::Vector2d d = Distort({(ideal_pixel.x() - cx) / fx, (ideal_pixel.y() - cy) / fy});
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Status Camera::Validate() const {
  if (width <= 0 || height <= 0) {
    return Status::Error("image size " + std::to_string(width) + " x " + std::to_string(height) + ": must be positive");
  }
  for (const auto& [name, f] : {std::pair{"fx", fx}, std::pair{"fy", fy}}) {
    if (!std::isfinite(f)) return Status::Error(std::string("focal length ") + name + ": not a finite number");
  }
  if (!(fx > 0) || !(fy > 0)) {
    return Status::Error("focal lengths fx = " + FormatNumber(fx) + ", fy = " + FormatNumber(fy) +
                         ": must be positive");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) return Status::Error("principal point: not finite");
  for (double k : distortion) {
    if (!std::isfinite(k)) return Status::Error("distortion_coefficients: not finite");
  }
  return Status::Ok();
}

IdealPixelMap::IdealPixelMap(const Camera& camera) : camera_(camera), width_(camera.width), height_(camera.height) {
  xy_.assign(2 * static_cast<size_t>(width_) * height_, std::numeric_limits<float>::quiet_NaN());
  for (int v = 0; v < height_; ++v) {
    std::optional<Eigen::Vector2d> previous;
    for (int u = 0; u < width_; ++u) {
      std::optional<Eigen::Vector2d> xy = camera.Undistort(Eigen::Vector2d(u, v), previous ? &*previous : nullptr);
      if (!xy && previous) xy = camera.Undistort(Eigen::Vector2d(u, v));
      if (xy) {
        const size_t k = 2 * (static_cast<size_t>(v) * width_ + u);
        xy_[k] = static_cast<float>(camera.fx * xy->x() + camera.cx);
        xy_[k + 1] = static_cast<float>(camera.fy * xy->y() + camera.cy);
      }
      previous = xy;
    }
  }
}

std::string CameraToOpenCvYaml(const Camera& camera, const CameraFileExtras& extras) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << "%YAML:1.0\n---\n";
  std::istringstream comment(extras.comment);
  for (std::string line; std::getline(comment, line);) out << "# " << line << "\n";
  if (!extras.calibration_time.empty()) out << "calibration_time: \"" << extras.calibration_time << "\"\n";
  if (extras.views > 0) out << "nr_of_frames: " << extras.views << "\n";
  out << "image_width: " << camera.width << "\nimage_height: " << camera.height << "\nflags: 0\n";
  out << Matrix("camera_matrix", 3, 3, {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1});
  out << Matrix("distortion_coefficients", 5, 1,
                std::vector<double>(camera.distortion.begin(), camera.distortion.end()));
  if (extras.rms_px >= 0) out << "avg_reprojection_error: " << FormatNumber(extras.rms_px) << "\n";
  if (!extras.std_dev.empty()) {
    out << "# standard deviations of fx, fy, cx, cy, k1, k2, p1, p2, k3\n"
        << Matrix("intrinsics_std_dev", static_cast<int>(extras.std_dev.size()), 1, extras.std_dev);
  }
  if (!extras.per_view_rms_px.empty()) {
    out << Matrix("per_view_reprojection_errors", static_cast<int>(extras.per_view_rms_px.size()), 1,
                  extras.per_view_rms_px);
  }
  return out.str();
}

Status SaveCamera(const Camera& camera, const std::string& path, const CameraFileExtras& extras) {
  return WriteFileAtomically(path, CameraToOpenCvYaml(camera, extras));
}

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
    return reader.ReadRos(yaml);
  }
  return reader.ReadRos(text);
}

StatusOr<Camera> LoadCamera(const std::string& path_or_name) {
  std::error_code error;
  if (path_or_name == kSimulatedCameraName && !std::filesystem::exists(path_or_name, error)) return SimulatedCamera();
  StatusOr<std::string> text = ReadFileToString(path_or_name);
  if (!text.ok()) {
    return Status::Error(text.status().message() + " (a camera file, or the built-in name " +
                         std::string(kSimulatedCameraName) + ")");
  }
  return ParseCameraFile(*text, path_or_name);
}

Camera SimulatedCamera() {
  Camera camera;
  camera.width = 1024;
  camera.height = 768;
  camera.fx = camera.fy = 903.2;  // 4.2 mm / 4.65 µm
  camera.cx = 515.3;              // a few pixels off the image centre (511.5, 383.5),
  camera.cy = 380.1;              // as a real lens mount is
  camera.distortion = {-0.28, 0.09, 0.0004, -0.0003, -0.012};
  return camera;
}

}  // namespace hexcal

// Camera files out (camera.h): OpenCV FileStorage YAML, ROS camera_info YAML
// and a Kalibr camchain. Every number in the shortest form that reads back
// exactly (FormatNumber), so ParseCameraFile (camera_file.cc) returns the
// same camera bit for bit.
#include <algorithm>
#include <cmath>
#include <locale>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "vision/camera.h"

namespace hexcal {
namespace {

constexpr int kOpenCvRationalModelFlag = 0x4000;  // cv::CALIB_RATIONAL_MODEL, in the file's `flags`

std::string Matrix(const std::string& name, int rows, int cols, const std::vector<double>& data) {
  std::string text = name + ": !!opencv-matrix\n   rows: " + std::to_string(rows) +
                     "\n   cols: " + std::to_string(cols) + "\n   dt: d\n   data: [ ";
  // NaN: a standard deviation the views do not determine (YAML's and OpenCV's spelling).
  for (size_t i = 0; i < data.size(); ++i)
    text += (i ? ", " : "") + (std::isfinite(data[i]) ? FormatNumber(data[i]) : ".nan");
  return text + " ]\n";
}

// The `distortion_model` name hexcal writes (ROS's; ParseCameraFile reads it).
const char* DistortionName(CameraModel model) {
  switch (model) {
    case CameraModel::kRational:
      return "rational_polynomial";
    case CameraModel::kPinholeEqui:
      return "equidistant";
    case CameraModel::kRadTan:
      break;
  }
  return "plumb_bob";
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// FormatNumber's shortest exact text, spelled so that YAML 1.1 (PyYAML, which
// ROS's and Kalibr's Python tools read with) resolves it as a float: its float
// pattern needs a '.' and a signed exponent, so "903" would be an int (Kalibr
// refuses an int focal length) and "1e-05" a string. "903.0" and "1.0e-05"
// are the same doubles to every reader.
std::string YamlFloat(double value) {
  std::string text = FormatNumber(value);
  if (text.find('.') == std::string::npos) {
    const size_t e = text.find('e');
    text.insert(e == std::string::npos ? text.size() : e, ".0");
  }
  return text;
}

std::string FlowList(const std::vector<double>& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + YamlFloat(values[i]);
  return text + "]";
}

// camera_calibration_parsers' {rows, cols, data} block under `key`.
std::string RosMatrix(const std::string& key, int rows, int cols, const std::vector<double>& data) {
  return key + ":\n  rows: " + std::to_string(rows) + "\n  cols: " + std::to_string(cols) +
         "\n  data: " + FlowList(data) + "\n";
}

std::vector<double> Coefficients(const Camera& camera) {
  return std::vector<double>(camera.distortion.begin(), camera.distortion.begin() + camera.NumCoefficients());
}

}  // namespace

std::string CameraToOpenCvYaml(const Camera& camera, const CameraFileExtras& extras) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << "%YAML:1.0\n---\n";
  std::istringstream comment(extras.comment);
  for (std::string line; std::getline(comment, line);) out << "# " << line << "\n";
  if (!extras.calibration_time.empty()) out << "calibration_time: \"" << extras.calibration_time << "\"\n";
  if (extras.views > 0) out << "nr_of_frames: " << extras.views << "\n";
  out << "image_width: " << camera.width << "\nimage_height: " << camera.height << "\n";
  out << "flags: " << (camera.model == CameraModel::kRational ? kOpenCvRationalModelFlag : 0) << "\n";
  // OpenCV's readers ignore this key; hexcal's and ROS's read the model from it.
  if (camera.model != CameraModel::kRadTan) out << "distortion_model: " << DistortionName(camera.model) << "\n";
  out << Matrix("camera_matrix", 3, 3, {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1});
  const int coefficients = camera.NumCoefficients();
  out << Matrix("distortion_coefficients", coefficients, 1, Coefficients(camera));
  if (extras.rms_px >= 0) out << "avg_reprojection_error: " << FormatNumber(extras.rms_px) << "\n";
  if (!extras.std_dev.empty()) {
    const std::vector<std::string> names = camera.ParameterNames();
    if (extras.std_dev.size() == names.size()) out << "# standard deviations of " << Join(names) << "\n";
    if (!std::all_of(extras.std_dev.begin(), extras.std_dev.end(), [](double s) { return std::isfinite(s); }))
      out << "# .nan: not determined by the views (the model has more freedom than they constrain)\n";
    out << Matrix("intrinsics_std_dev", static_cast<int>(extras.std_dev.size()), 1, extras.std_dev);
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

const char* CameraFileFormatName(CameraFileFormat format) {
  switch (format) {
    case CameraFileFormat::kRos:
      return "ros";
    case CameraFileFormat::kKalibr:
      return "kalibr";
    case CameraFileFormat::kOpenCv:
      break;
  }
  return "opencv";
}

std::optional<CameraFileFormat> CameraFileFormatFromName(const std::string& name) {
  for (CameraFileFormat format : {CameraFileFormat::kOpenCv, CameraFileFormat::kRos, CameraFileFormat::kKalibr}) {
    if (name == CameraFileFormatName(format)) return format;
  }
  return std::nullopt;
}

bool IsRosCameraName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::string CameraToRosYaml(const Camera& camera, const std::string& camera_name) {
  const double fx = camera.fx, fy = camera.fy, cx = camera.cx, cy = camera.cy;
  const int coefficients = camera.NumCoefficients();
  // camera_calibration_parsers' keys in its order (parse_yml.cpp).
  return "image_width: " + std::to_string(camera.width) + "\nimage_height: " + std::to_string(camera.height) +
         "\ncamera_name: " + camera_name + "\n" + RosMatrix("camera_matrix", 3, 3, {fx, 0, cx, 0, fy, cy, 0, 0, 1}) +
         "distortion_model: " + DistortionName(camera.model) + "\n" +
         RosMatrix("distortion_coefficients", 1, coefficients, Coefficients(camera)) +
         RosMatrix("rectification_matrix", 3, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1}) +
         RosMatrix("projection_matrix", 3, 4, {fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0});
}

StatusOr<std::string> CameraToKalibrYaml(const Camera& camera) {
  const std::string refused = "a Kalibr camchain cannot hold this camera: ";
  if (camera.model == CameraModel::kRational) {
    return Status::BadInput(refused + "Kalibr has no rational model (k1 k2 p1 p2 k3 k4 k5 k6); its pinhole camera " +
                            "takes radtan (k1 k2 p1 p2) or equidistant; write it --to ros or opencv");
  }
  if (camera.model == CameraModel::kRadTan && camera.distortion[4] != 0) {
    return Status::BadInput(refused + "k3 = " + FormatNumber(camera.distortion[4]) +
                            ", and Kalibr's radtan has k1 k2 p1 p2 only (k3 = 0); write it --to ros or opencv");
  }
  // Kalibr's CameraParameters.checkIntrinsics refuses these.
  if (camera.cx < 0 || camera.cy < 0) {
    return Status::BadInput(refused + "principal point (" + FormatNumber(camera.cx) + ", " + FormatNumber(camera.cy) +
                            ") is negative, which Kalibr's reader refuses");
  }
  const bool fisheye = camera.model == CameraModel::kPinholeEqui;
  const std::vector<double> coefficients(camera.distortion.begin(), camera.distortion.begin() + 4);
  // kalibr_calibrate_cameras also writes rostopic (and cam_overlaps), which
  // only the tools that read a bag need; hexcal does not know the topic.
  return "# Kalibr camchain; kalibr_calibrate_imu_camera also needs cam0's rostopic: the image topic\n"
         "cam0:\n  camera_model: pinhole\n  intrinsics: " +
         FlowList({camera.fx, camera.fy, camera.cx, camera.cy}) +
         "\n  distortion_model: " + (fisheye ? "equidistant" : "radtan") +
         "\n  distortion_coeffs: " + FlowList(coefficients) + "\n  resolution: [" + std::to_string(camera.width) +
         ", " + std::to_string(camera.height) + "]\n";
}

StatusOr<std::string> CameraToText(const Camera& camera, CameraFileFormat format, const std::string& ros_camera_name) {
  if (Status s = camera.Validate(); !s.ok()) return s;
  switch (format) {
    case CameraFileFormat::kRos:
      if (!IsRosCameraName(ros_camera_name)) {
        return Status::BadInput("camera name " + Excerpt(ros_camera_name) +
                                ": ROS takes letters, digits and '_' only (camera_info_manager)");
      }
      return CameraToRosYaml(camera, ros_camera_name);
    case CameraFileFormat::kKalibr:
      return CameraToKalibrYaml(camera);
    case CameraFileFormat::kOpenCv:
      break;
  }
  return CameraToOpenCvYaml(camera);
}

}  // namespace hexcal

// hexcal camera show CAMERA [--json]
// hexcal camera convert CAMERA --to opencv|ros|kalibr --out FILE [--camera-name NAME] [--force] [--json]
//
// CAMERA: any camera file ParseCameraFile reads (OpenCV YAML or XML, ROS
// camera_info, Kalibr camchain) or the built-in name sim-4.2mm-1024x768.
// convert writes the same camera in another format (vision/camera.h
// CameraToText), atomically, never over an existing file without --force.
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "vision/camera.h"

namespace hexcal::cli {
namespace {

struct CameraShowOptions {
  std::string camera;
  bool json = false;
};

struct CameraConvertOptions {
  std::string camera, to, out;
  std::string camera_name = "camera";  // ROS camera_name
  bool force = false, json = false;
};

// What ROS and Kalibr call the model, for the reader of `show`.
const char* ModelAliases(CameraModel model) {
  switch (model) {
    case CameraModel::kRational:
      return "OpenCV CALIB_RATIONAL_MODEL, ROS rational_polynomial";
    case CameraModel::kPinholeEqui:
      return "equidistant fisheye: cv::fisheye, ROS equidistant, Kalibr pinhole + equidistant";
    case CameraModel::kRadTan:
      break;
  }
  return "OpenCV's 5 coefficients, ROS plumb_bob, Kalibr radtan when k3 = 0";
}

nlohmann::json OptionalJson(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json();
}

nlohmann::json CameraJson(const std::string& source, const Camera& camera) {
  const std::vector<std::string> names = camera.ParameterNames();
  const std::vector<double> values = camera.ParameterValues();
  const FieldOfView fov = CameraFieldOfView(camera);
  return {{"source", source},
          {"model", CameraModelName(camera.model)},
          {"width", camera.width},
          {"height", camera.height},
          {"fx", camera.fx},
          {"fy", camera.fy},
          {"cx", camera.cx},
          {"cy", camera.cy},
          {"coefficient_names", std::vector<std::string>(names.begin() + 4, names.end())},
          {"coefficients", std::vector<double>(values.begin() + 4, values.end())},
          {"field_of_view_deg",
           {{"horizontal", OptionalJson(fov.horizontal_deg)},
            {"vertical", OptionalJson(fov.vertical_deg)},
            {"diagonal", OptionalJson(fov.diagonal_deg)}}}};
}

std::string Degrees(const std::optional<double>& angle) {
  if (!angle) return "n/a (past what the model inverts)";
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f deg", *angle);
  return text;
}

void PrintCamera(const std::string& source, const Camera& camera, std::ostream& out) {
  out << "camera " << source << ": " << CameraModelName(camera.model) << " (" << ModelAliases(camera.model) << "), "
      << camera.width << " x " << camera.height << " px\n";
  // The file's numbers exactly (FormatNumber): what convert will write.
  const std::vector<std::string> names = camera.ParameterNames();
  const std::vector<double> values = camera.ParameterValues();
  for (size_t i = 0; i < names.size(); ++i) {
    if (i == 0 || i == 4) out << (i == 0 ? "  pinhole (px):" : "  distortion:  ");
    out << " " << names[i] << " " << FormatNumber(values[i]);
    if (i == 3 || i + 1 == names.size()) out << "\n";
  }
  const FieldOfView fov = CameraFieldOfView(camera);
  out << "  field of view: " << Degrees(fov.horizontal_deg) << " horizontal, " << Degrees(fov.vertical_deg)
      << " vertical, " << Degrees(fov.diagonal_deg) << " diagonal\n";
}

int RunCameraShow(const CameraShowOptions& options, std::ostream& out, std::ostream& err) {
  StatusOr<Camera> camera = LoadCamera(options.camera);
  if (!camera.ok()) return ReportError(err, "camera show", camera.status());
  if (options.json) {
    out << JsonText(CameraJson(options.camera, *camera));
  } else {
    PrintCamera(options.camera, *camera, out);
  }
  return kExitOk;
}

int RunCameraConvert(const CameraConvertOptions& options, std::ostream& out, std::ostream& err) {
  const std::optional<CameraFileFormat> format = CameraFileFormatFromName(options.to);
  if (!format) {
    return ReportError(
        err, "camera convert",
        Status::BadInput("--to: unknown format " + Excerpt(options.to) + "; accepted: opencv, ros, kalibr"));
  }
  if (*format == CameraFileFormat::kRos && !IsRosCameraName(options.camera_name)) {
    return ReportError(err, "camera convert",
                       Status::BadInput("--camera-name: " + Excerpt(options.camera_name) +
                                        " is not a ROS camera name: letters, digits and '_' only"));
  }
  if (Status s = CheckOutputFree(options.out, options.force); !s.ok()) return ReportError(err, "camera convert", s);
  StatusOr<Camera> camera = LoadCamera(options.camera);
  if (!camera.ok()) return ReportError(err, "camera convert", camera.status());
  // A refusal (Kalibr and the rational model, say) names the camera it is about.
  StatusOr<std::string> text = CameraToText(*camera, *format, options.camera_name);
  if (!text.ok()) return ReportError(err, "camera convert", text.status().Prefixed(options.camera + ": "));
  if (Status s = WriteFileAtomically(options.out, *text); !s.ok()) return ReportError(err, "camera convert", s);
  if (options.json) {
    out << JsonText(nlohmann::json{
        {"out", options.out}, {"to", CameraFileFormatName(*format)}, {"camera", CameraJson(options.camera, *camera)}});
  } else {
    out << "wrote " << options.out << ": " << CameraFileFormatName(*format) << " file of the "
        << CameraModelName(camera->model) << " camera " << options.camera << " (" << camera->width << " x "
        << camera->height << ")\n";
  }
  return kExitOk;
}

}  // namespace

void AddCameraCommand(CLI::App& app, int* exit_code) {
  CLI::App* camera = app.add_subcommand("camera", "show a camera file or convert it (OpenCV, ROS, Kalibr)");
  camera->require_subcommand(1);
  const char* camera_help = "camera file (OpenCV YAML/XML, ROS camera_info, Kalibr camchain) or sim-4.2mm-1024x768";

  auto show = std::make_shared<CameraShowOptions>();
  CLI::App* show_sub = camera->add_subcommand("show", "print a camera's model, size, intrinsics and field of view");
  show_sub->add_option("camera", show->camera, camera_help)->required();
  show_sub->add_flag("--json", show->json, "print one JSON object on stdout");
  show_sub->callback([=] { *exit_code = RunCameraShow(*show, std::cout, std::cerr); });

  auto convert = std::make_shared<CameraConvertOptions>();
  CLI::App* convert_sub = camera->add_subcommand("convert", "write a camera as OpenCV, ROS camera_info or Kalibr YAML");
  convert_sub->add_option("camera", convert->camera, camera_help)->required();
  convert_sub->add_option("--to", convert->to, "output format: opencv, ros (camera_info), kalibr (camchain)")
      ->required();
  convert_sub->add_option("--out", convert->out, "file to write")->required();
  convert_sub->add_option("--camera-name", convert->camera_name, "--to ros: camera_name (letters, digits, _)")
      ->capture_default_str();
  convert_sub->add_flag("--force", convert->force, "overwrite an existing --out file");
  convert_sub->add_flag("--json", convert->json, "print one JSON object on stdout");
  convert_sub->callback([=] { *exit_code = RunCameraConvert(*convert, std::cout, std::cerr); });
}

}  // namespace hexcal::cli

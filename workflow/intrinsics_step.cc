#include "workflow/intrinsics_step.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "charts/chart_render.h"
#include "core/atomic_file.h"
#include "report/corner_charts.h"
#include "report/corner_report_section.h"
#include "vision/image_codecs.h"
#include "vision/intrinsics_diagnosis.h"
#include "vision/measure.h"

namespace hexcal::workflow {
namespace {

// "camera.yaml" -> "camera.coverage.png"
std::string DefaultCoveragePath(const std::string& out) {
  std::filesystem::path path(out);
  path.replace_extension(".coverage.png");
  return path.string();
}

// "camera.yaml" -> "camera.residuals.png", written when charts can be drawn here.
std::string WriteResidualField(const IntrinsicsResult& result, const std::string& coverage) {
  std::filesystem::path path(coverage);
  path.replace_extension();  // "camera.coverage"
  path.replace_extension(".residuals.png");
  const CornerResidualTable table = CornerTableOf(result);
  StatusOr<std::string> png =
      charts::ChartPng(ResidualFieldChart(table.corners, result.camera.width, result.camera.height));
  if (!png.ok() || !WriteFileAtomically(path.string(), *png).ok()) return "";
  return path.string();
}

}  // namespace

CornerResidualTable CornerTableOf(const IntrinsicsResult& result) {
  CornerResidualTable table;
  for (const CalibrationView& view : result.views) table.images.push_back(view.file);
  table.corners = result.corner_residuals;
  return table;
}

StatusOr<IntrinsicsOutcome> CalibrateCameraFromFiles(const std::vector<std::string>& files, const Target& target,
                                                     const IntrinsicsOptions& options, const std::string& out,
                                                     const std::string& coverage, const JobHooks& hooks) {
  StatusOr<IntrinsicsResult> result = CalibrateIntrinsics(files, target, options, hooks);
  // Unusable images (sizes, too few views) are the usual cause: bad input.
  if (!result.ok()) return result.status();
  if (Status s = CheckIntrinsicsFit(*result, target, options.max_rms_px); !s.ok()) return s;
  if (Status s = SaveCamera(result->camera, out, ExtrasOf(*result)); !s.ok()) return s;
  if (!coverage.empty()) {
    StatusOr<std::string> png = EncodePng(CoverageImage(*result));
    if (!png.ok()) return png.status().AsFailure();
    if (Status s = WriteFileAtomically(coverage, *png); !s.ok()) return s;
  }
  const std::string residuals = coverage.empty() ? "" : WriteResidualField(*result, coverage);
  return IntrinsicsOutcome{std::move(*result), out,      coverage, static_cast<int>(files.size()),
                           options.outlier_factor, residuals};
}

StatusOr<IntrinsicsOutcome> CalibrateCameraFromFolder(const IntrinsicsRequest& request, const JobHooks& hooks) {
  StatusOr<Target> target = LoadTarget(request.target);
  if (!target.ok()) return target.status();
  StatusOr<std::vector<std::string>> files = ListImages(request.images);
  if (!files.ok()) return files.status();
  if (Status s = CheckOutputFree(request.out, request.force); !s.ok()) return s;
  const std::string coverage = request.coverage.empty() ? DefaultCoveragePath(request.out) : request.coverage;
  return CalibrateCameraFromFiles(*files, *target, request.options, request.out, coverage, hooks);
}

nlohmann::json ToJson(const IntrinsicsOutcome& outcome) {
  const IntrinsicsResult& result = outcome.result;
  const Camera& c = result.camera;
  const std::vector<std::string> names = c.ParameterNames();
  const std::vector<double> values = c.ParameterValues();
  nlohmann::json parameters, views = nlohmann::json::array();
  for (size_t i = 0; i < names.size(); ++i) {
    // std_dev null: the model's calibration does not estimate it.
    parameters[names[i]] = {
        {"value", values[i]},
        {"std_dev", i < result.std_dev.size() ? nlohmann::json(result.std_dev[i]) : nlohmann::json()}};
  }
  for (const CalibrationView& view : result.views) {
    views.push_back({{"file", view.file},
                     {"used", view.used},
                     {"tags", view.tags},
                     {"rms_px", view.rms_px},
                     {"reason", view.reason}});
  }
  const CrossValidation& cross = result.cross_validation;
  nlohmann::json cross_json;  // null: too few views to split
  if (cross.done) {
    cross_json = {{"views", {cross.views_a, cross.views_b}},
                  {"rms_px", cross.rms_px},
                  {"max_px", cross.max_px},
                  {"max_sigma", cross.z.empty() ? nlohmann::json() : nlohmann::json(cross.max_z)},
                  {"verdict", CrossValidationGood(cross) ? "good" : "poor"},
                  {"good_max_rms_px", kCrossHalvesGoodPx},
                  {"good_max_sigma", kCrossSigmaGood}};
  }
  return {{"out", outcome.out},
          {"model", CameraModelName(c.model)},
          {"coverage", outcome.coverage},
          {"coverage_fraction", CoverageFraction(result)},
          {"image_width", c.width},
          {"image_height", c.height},
          {"rms_px", result.rms_px},
          {"used_views", result.used_views},
          {"parameters", parameters},
          {"views", views},
          {"cross_validation", cross_json},
          {"residuals", outcome.residuals},
          {"corners", CornerDiagnosticsJson(CornerTableOf(result), c.width, c.height)}};
}

std::string FormatIntrinsicsSummary(const IntrinsicsOutcome& outcome) {
  const IntrinsicsResult& result = outcome.result;
  const Camera& c = result.camera;
  const std::vector<std::string> names = c.ParameterNames();
  const std::vector<double> values = c.ParameterValues();
  std::ostringstream out;
  out << "camera " << c.width << " x " << c.height << " (" << CameraModelName(c.model) << ") from " << result.used_views
      << " of " << outcome.images << " images, RMS " << result.rms_px << " px\n";
  for (size_t i = 0; i < names.size(); ++i) {
    out << "  " << names[i] << " = " << values[i];
    if (i < result.std_dev.size()) {
      if (std::isfinite(result.std_dev[i])) {
        out << " +- " << result.std_dev[i];
      } else {
        out << " +- ? (not determined by the views)";
      }
    }
    out << "\n";
  }
  if (result.std_dev.empty()) out << "  (no standard deviations: cv::fisheye::calibrate does not estimate them)\n";
  for (const CalibrationView& view : result.views) {
    if (!view.used) out << "  not used: " << view.file << ": " << view.reason << "\n";
  }
  if (const std::string worst = DescribeWorstView(result, outcome.outlier_factor); !worst.empty()) {
    out << "  " << worst << "\n";
  }
  out << "  " << DescribeCrossValidation(result.cross_validation) << "\n";
  const CornerResidualTable corners = CornerTableOf(result);
  out << "  per corner: " << FormatCornerFigures(corners, c.width, c.height) << "\n";
  out << "  worst corners (residual = projected - detected):\n" << FormatWorstCorners(corners);
  out << "written to " << outcome.out;
  if (!outcome.coverage.empty())
    out << "; corner coverage " << 100 * CoverageFraction(result) << " % in " << outcome.coverage;
  if (!outcome.residuals.empty()) out << "; residual field in " << outcome.residuals;
  return out.str() + "\n";
}

}  // namespace hexcal::workflow

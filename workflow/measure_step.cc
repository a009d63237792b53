#include "workflow/measure_step.h"

#include <filesystem>
#include <sstream>

#include "core/atomic_file.h"

namespace hexcal::workflow {
std::string DiagnoseMeasurements(const MeasureResult& result) { return DiagnoseBoardFits(result.counts); }

std::string DiagnoseBoardFits(const std::map<std::string, int>& counts) {
  auto count = [&](const char* status) {
    const auto it = counts.find(status);
    return it == counts.end() ? 0 : it->second;
  };
  const int high = count("high_rms");
  const int with_board = high + count("ok") + count("ambiguous");
  if (high == 0 || 2 * high < with_board) return "";
  return std::to_string(high) + " of " + std::to_string(with_board) +
         " images that show the board fit it badly (reprojection RMS over the limit): a systematic error, not bad "
         "images. Check that the target file describes the board as printed (rows, cols, tag_size and its "
         "length_unit, tag_spacing, first_id or its ids or tags, border_bits) and that the camera file is this "
         "camera's, at this "
         "resolution and with a model that fits its lens";
}

namespace {

nlohmann::json MeasurementJson(const ImageMeasurement& m) {
  nlohmann::json j = {{"file", m.file},
                      {"status", PoseStatusName(m.pose.status)},
                      {"message", m.pose.message},
                      {"tags", m.pose.num_tags}};
  if (m.pose.has_pose) {
    const Vector6d v = VectorFromPose(m.pose.camera_from_target, EulerConvention::kXYZ);
    static const char* kNames[6] = {"x", "y", "z", "q1", "q2", "q3"};
    for (int k = 0; k < 6; ++k) {
      j["pose"][kNames[k]] = v[k];
      j["sigma"][kNames[k]] = std::sqrt(std::max(0.0, m.pose.covariance_vector(k, k)));
    }
    j["rms_px"] = m.pose.rms_px;
  }
  return j;
}

}  // namespace

int MeasureResult::ok() const {
  auto it = counts.find("ok");
  return it == counts.end() ? 0 : it->second;
}

namespace {

// `relative`: file names without their folder, so that the table moves with the images.
StatusOr<MeasureResult> MeasureAndWrite(const std::vector<std::string>& files, const Camera& camera,
                                        const Target& target, const MeasureOptions& options, const std::string& out,
                                        bool relative, const JobHooks& hooks) {
  StatusOr<std::vector<ImageMeasurement>> rows = MeasureImages(files, camera, target, options, hooks);
  if (!rows.ok()) return rows.status().AsFailure();
  MeasureResult result{out, LengthUnitName(target.length_unit), std::move(*rows), {}};
  for (ImageMeasurement& m : result.rows) {
    if (relative) m.file = std::filesystem::path(m.file).filename().string();
    ++result.counts[PoseStatusName(m.pose.status)];
  }
  if (Status s = WriteImageMeasurementsCsv(out, result.rows); !s.ok()) return s;
  return result;
}

}  // namespace

StatusOr<MeasureResult> MeasureFolder(const MeasureRequest& request, const JobHooks& hooks) {
  StatusOr<Camera> camera = LoadCamera(request.camera);
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(request.target);
  if (!target.ok()) return target.status();
  std::string error;
  if (!request.options.IsValid(&error)) return Status::BadInput(error);
  StatusOr<std::vector<std::string>> files = ListImages(request.images);
  if (!files.ok()) return files.status();
  if (Status s = CheckOutputFree(request.out, request.force); !s.ok()) return s;
  std::error_code fs_error;
  const bool folder = std::filesystem::is_directory(request.images, fs_error);
  return MeasureAndWrite(*files, *camera, *target, request.options, request.out, folder, hooks);
}

StatusOr<MeasureResult> MeasureFiles(const std::vector<std::string>& files, const Camera& camera,
                                     const Target& target, const MeasureOptions& options, const std::string& out,
                                     const JobHooks& hooks) {
  return MeasureAndWrite(files, camera, target, options, out, /*relative=*/true, hooks);
}

nlohmann::json ToJson(const MeasureResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ImageMeasurement& m : result.rows) rows.push_back(MeasurementJson(m));
  return {{"out", result.out},
          {"images", result.rows.size()},
          {"counts", result.counts},
          {"length_unit", result.length_unit},
          {"results", rows}};
}

std::string FormatMeasureSummary(const MeasureResult& result) {
  std::ostringstream out;
  out << result.rows.size() << " images:";
  for (const auto& [status, count] : result.counts) {
    if (count) out << " " << count << " " << status;
  }
  out << "; written to " << result.out << " (camera_from_target, " << result.length_unit << " and degrees)\n";
  for (const ImageMeasurement& m : result.rows) {
    if (m.pose.status != PoseStatus::kOk)
      out << "  " << m.file << ": " << PoseStatusName(m.pose.status) << ": " << m.pose.message << "\n";
  }
  return out.str();
}

}  // namespace hexcal::workflow

#include "vision/measure.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/parallel.h"

namespace hexcal {
namespace {

bool HasImageExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".tif" ||
         extension == ".tiff";
}

}  // namespace

bool MeasureOptions::IsValid(std::string* error) const {
  if (!detector.IsValid(error) || !pose.IsValid(error)) return false;
  if (threads < 0 || threads > 64) {
    if (error) *error = "threads: must be in 0..64 (0: every core)";
    return false;
  }
  return true;
}

StatusOr<std::vector<std::string>> ListImages(const std::string& folder_or_file) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(folder_or_file, error);
  if (!fs::is_directory(status)) {
    std::error_code link_error;
    const bool link = fs::is_symlink(fs::symlink_status(folder_or_file, link_error));
    if ((error || !fs::exists(status)) && !link) return Status::BadInput(folder_or_file + ": no such file or folder");
    // One image: a FIFO, a device or a dangling link is bad input here, not an unreadable row later.
    if (Status s = CheckFileForReading(folder_or_file, kMaxImageBytes); !s.ok()) return s;
    return std::vector<std::string>{folder_or_file};
  }
  std::vector<std::string> files;
  for (fs::directory_iterator it(folder_or_file, error), end; !error && it != end; it.increment(error)) {
    if (!it->is_directory(error) && HasImageExtension(it->path())) files.push_back(it->path().string());
  }
  if (error) return FileSystemError(folder_or_file, "cannot list the folder", error.value());
  if (files.empty()) return Status::BadInput(folder_or_file + ": no PNG, JPEG or TIFF images in the folder");
  std::sort(files.begin(), files.end());
  return files;
}

ImageMeasurement MeasureImage(TagDetector& detector, const cv::Mat& gray, const Camera& camera, const Target& target,
                              const BoardPoseOptions& options, bool keep_observation) {
  ImageMeasurement measurement;
  if (gray.cols != camera.width || gray.rows != camera.height) {
    measurement.pose.status = PoseStatus::kWrongSize;
    measurement.pose.message = "image is " + std::to_string(gray.cols) + " x " + std::to_string(gray.rows) +
                               ", the camera " + std::to_string(camera.width) + " x " + std::to_string(camera.height);
    return measurement;
  }
  const Detections detections = detector.Detect(gray);
  const BoardObservation observation = MatchToTarget(target, detections);
  measurement.pose = EstimateBoardPose(camera, observation, options);
  measurement.rejected_tags = static_cast<int>(detections.rejected.size());
  measurement.foreign_tags = observation.foreign_tags;
  if (keep_observation) measurement.observation = observation;
  if (measurement.pose.status == PoseStatus::kNoTarget && !detections.tags.empty()) {
    measurement.pose.message += " (" + std::to_string(observation.foreign_tags) + " tags of other targets)";
  }
  return measurement;
}

StatusOr<std::vector<ImageMeasurement>> MeasureImages(const std::vector<std::string>& files, const Camera& camera,
                                                      const Target& target, const MeasureOptions& options,
                                                      const JobHooks& hooks) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput("measure options: " + error);
  const int count = static_cast<int>(files.size());
  const int workers = ParallelWorkers(count, options.threads);
  auto ideal = std::make_shared<const IdealPixelMap>(camera);
  StatusOr<std::vector<std::unique_ptr<TagDetector>>> created = CreateWorkerDetectors(ForTarget(options.detector, target), ideal, workers);
  if (!created.ok()) return created.status();
  std::vector<std::unique_ptr<TagDetector>> detectors = std::move(*created);
  std::vector<ImageMeasurement> measurements(files.size());
  const bool finished = ParallelFor(
      count, options.threads,
      [&](int index, int worker) {
        const std::string& file = files[static_cast<size_t>(index)];
        ImageMeasurement& measurement = measurements[static_cast<size_t>(index)];
        StatusOr<cv::Mat> image = LoadGrayImage(file);
        if (!image.ok()) {
          measurement.pose.status = PoseStatus::kUnreadable;
          measurement.pose.message = image.status().message();
        } else {
          measurement = MeasureImage(*detectors[static_cast<size_t>(worker)], *image, camera, target, options.pose,
                                     options.keep_observations);
        }
        measurement.file = file;
      },
      hooks);
  if (!finished) return Status::Cancelled("measure: cancelled");
  return measurements;
}

std::vector<std::string> ImageMeasurementColumns() {
  std::vector<std::string> columns = {"file",     "x",        "y",        "z",        "q1",     "q2",
                                      "q3",       "sigma_x",  "sigma_y",  "sigma_z",  "sigma_q1", "sigma_q2",
                                      "sigma_q3", "rms_px",   "tags",     "status",   "message"};
  const char* names[6] = {"x", "y", "z", "q1", "q2", "q3"};
  for (int a = 0; a < 6; ++a)
    for (int b = a + 1; b < 6; ++b) columns.push_back(std::string("corr_") + names[a] + "_" + names[b]);
  return columns;
}

std::optional<Matrix6d> CovarianceFromSigmasAndCorrelations(const std::array<double, 6>& sigma,
                                                            const std::array<double, 15>& correlation) {
  Matrix6d covariance = Matrix6d::Zero();
  int k = 0;
  for (int a = 0; a < 6; ++a) {
    if (!(sigma[a] >= 0) || !std::isfinite(sigma[a])) return std::nullopt;
    covariance(a, a) = sigma[a] * sigma[a];
    for (int b = a + 1; b < 6; ++b, ++k) {
      if (!(std::abs(correlation[k]) <= 1)) return std::nullopt;
      covariance(a, b) = covariance(b, a) = correlation[k] * sigma[a] * sigma[b];
    }
  }
  return covariance;
}

std::vector<std::string> ImageMeasurementRow(const ImageMeasurement& measurement) {
  std::vector<std::string> row = {measurement.file};
  const BoardPose& pose = measurement.pose;
  if (pose.has_pose) {
    const Vector6d v = VectorFromPose(pose.camera_from_target, EulerConvention::kXYZ);
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(std::sqrt(std::max(0.0, pose.covariance_vector(k, k)))));
    row.push_back(FormatNumber(pose.rms_px));
  } else {
    row.insert(row.end(), 13, "");
  }
  row.push_back(std::to_string(pose.num_tags));
  row.push_back(PoseStatusName(pose.status));
  row.push_back(pose.message);
  for (int a = 0; a < 6; ++a) {
    for (int b = a + 1; b < 6; ++b) {
      const double scale = std::sqrt(pose.covariance_vector(a, a) * pose.covariance_vector(b, b));
      row.push_back(pose.has_pose && scale > 0 ? FormatNumber(pose.covariance_vector(a, b) / scale) : "");
    }
  }
  return row;
}

StatusOr<std::vector<ImageMeasurementRecord>> ParseImageMeasurementsCsv(const std::string& text,
                                                                        const std::string& source) {
  StatusOr<CsvTable> table = ParseCsv(text, source);
  if (!table.ok()) return table.status();
  if (table->header != ImageMeasurementColumns())
    return Status::BadInput(source + ": not the columns hexcal measure writes; remove it to re-measure");
  std::vector<ImageMeasurementRecord> records;
  for (size_t r = 0; r < table->rows.size(); ++r) {
    ImageMeasurementRecord record;
    record.cells = table->rows[r];
    record.file = record.cells[0];
    record.ok = record.cells[15] == "ok";
    if (record.ok) {
      // Columns 1-6 the pose, 7-12 its σ, 17-31 the correlations.
      Vector6d v;
      std::array<double, 6> sigma;
      std::array<double, 15> correlation;
      for (int k = 0; k < 27; ++k) {
        const int column = k < 12 ? 1 + k : 17 + (k - 12);
        StatusOr<double> value = NumberAt(*table, r, column);
        if (!value.ok()) return value.status();
        (k < 6 ? v[k] : k < 12 ? sigma[k - 6] : correlation[k - 12]) = *value;
      }
      record.camera_from_target = PoseFromVector(v, EulerConvention::kXYZ);
      std::optional<Matrix6d> covariance = CovarianceFromSigmasAndCorrelations(sigma, correlation);
      if (!covariance)
        return Status::BadInput(source + ":" + std::to_string(r + 2) +
                                ": a sigma is negative or a correlation is outside [-1, 1]");
      record.covariance = *covariance;
    }
    records.push_back(std::move(record));
  }
  return records;
}

Status WriteImageMeasurementsCsv(const std::string& path, const std::vector<ImageMeasurement>& measurements) {
  std::vector<std::vector<std::string>> rows;
  for (const ImageMeasurement& measurement : measurements) rows.push_back(ImageMeasurementRow(measurement));
  return WriteCsv(path, ImageMeasurementColumns(), rows);
}

}  // namespace hexcal

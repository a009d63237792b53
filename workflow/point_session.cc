#include "workflow/point_session.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/point_fit.h"
#include "core/reflector_estimate.h"
#include "session/json_fields.h"
#include "session/session_models.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

}  // namespace

StatusOr<LoadedPoints> LoadPoints(const PointFiles& files) {
  StatusOr<PointSets> sets = LoadPointFile(files.points, files.default_sigma);
  if (!sets.ok()) return sets.status();
  LoadedPoints loaded{std::move(*sets), {}, files.reflectors.empty()};
  if (loaded.estimated) {
    StatusOr<std::vector<NamedPoint>> estimate = EstimateReflectors(loaded.sets);
    if (!estimate.ok()) return Status::BadInput(files.points + ": " + estimate.status().message());
    loaded.reflectors = std::move(*estimate);
    return loaded;
  }
  StatusOr<std::vector<NamedPoint>> parsed = LoadReflectorFile(files.reflectors);
  if (!parsed.ok()) return parsed.status();
  loaded.reflectors = std::move(*parsed);
  return loaded;
}

namespace {

// The point set of every row, by its pose name; a row without one is an error.
StatusOr<std::map<std::string, const PointSet*>> SetsOfRows(const LoadedPoints& loaded, const std::string& source,
                                                           const std::vector<LegsRow>& rows) {
  std::map<std::string, const PointSet*> by_name;
  for (const PointSet& set : loaded.sets) by_name[set.pose] = &set;
  std::map<std::string, const PointSet*> of_rows;
  for (const LegsRow& row : rows) {
    const auto found = by_name.find(row.image);
    if (found == by_name.end())
      return Status::BadInput("legs.csv:" + std::to_string(row.line) + ": pose '" + row.image + "' has no points in " +
                              source);
    of_rows[row.image] = found->second;
  }
  return of_rows;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// √3 · the median pose σ, per block of the covariance (position, angle).
NoiseModel NoiseFromFits(const std::map<std::string, SessionImagePose>& poses, const NoiseModel& declared) {
  std::vector<double> position, angle;
  for (const auto& [name, pose] : poses) {
    if (!pose.ok) continue;
    position.push_back(std::sqrt(pose.covariance.topLeftCorner<3, 3>().trace() / 3));
    angle.push_back(std::sqrt(pose.covariance.bottomRightCorner<3, 3>().trace() / 3));
  }
  NoiseModel noise = declared;
  if (position.empty()) return noise;
  noise.position = std::sqrt(3.0) * Median(position);
  noise.angle_deg = std::sqrt(3.0) * Median(angle);
  return noise;
}

}  // namespace

StatusOr<PointPoses> MeasurePointPoses(const PointFiles& files, const std::vector<LegsRow>& rows,
                                       const NoiseModel& noise, const JobHooks& hooks) {
  StatusOr<LoadedPoints> loaded = LoadPoints(files);
  if (!loaded.ok()) return loaded.status();
  StatusOr<std::map<std::string, const PointSet*>> sets = SetsOfRows(*loaded, files.points, rows);
  if (!sets.ok()) return sets.status();
  PointPoses measured;
  measured.reflectors = loaded->reflectors;
  measured.reflectors_estimated = loaded->estimated;
  for (const LegsRow& row : rows) {
    StatusOr<PointFit> fit = FitPointPose(loaded->reflectors, sets->at(row.image)->points);
    SessionImagePose& pose = measured.poses[row.image];
    if (!fit.ok()) {
      pose.status = "bad_points";
      ++measured.left_out;
      hooks.Note("warning: " + files.points + ": pose '" + row.image + "': " + fit.status().message() +
                 "; left out");
      continue;
    }
    pose = SessionImagePose{true, "ok", fit->pose, fit->covariance * (files.noise_factor * files.noise_factor)};
  }
  measured.noise = NoiseFromFits(measured.poses, noise);
  return measured;
}

namespace {

std::vector<std::string> PointPoseRow(const std::string& pose, const StatusOr<PointFit>& fit, size_t points) {
  std::vector<std::string> row = {pose};
  if (!fit.ok()) {  // the pose, 13 empty cells (pose, σ, rms), its point count and why
    row.resize(14);
    row.insert(row.end(), {std::to_string(points), "bad_points", fit.status().message()});
    return row;
  }
  const Vector6d v = VectorFromPose(fit->pose, EulerConvention::kXYZ);
  for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
  for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(std::sqrt(fit->covariance(k, k))));
  row.push_back(FormatNumber(fit->rms));
  row.push_back(std::to_string(points));
  row.push_back("ok");
  row.push_back("");
  return row;
}

}  // namespace

StatusOr<PointMeasureResult> MeasurePointFile(const PointFiles& files, const std::string& out, bool force) {
  std::error_code error;
  if (!force && fs::exists(fs::symlink_status(out, error)))
    return Status::BadInput(out + ": exists; use --force to replace it");
  StatusOr<LoadedPoints> loaded = LoadPoints(files);
  if (!loaded.ok()) return loaded.status();
  PointMeasureResult result;
  result.reflectors_estimated = loaded->estimated;
  std::vector<std::vector<std::string>> rows;
  for (const PointSet& set : loaded->sets) {
    const StatusOr<PointFit> fit = FitPointPose(loaded->reflectors, set.points);
    rows.push_back(PointPoseRow(set.pose, fit, set.points.size()));
    ++result.poses;
    result.fitted += fit.ok() ? 1 : 0;
  }
  const std::vector<std::string> header = {"pose", "x", "y", "z", "q1", "q2", "q3", "sigma_x", "sigma_y", "sigma_z",
                                           "sigma_q1", "sigma_q2", "sigma_q3", "rms", "points", "status", "message"};
  if (Status s = WriteCsv(out, header, rows); !s.ok()) return s;
  return result;
}

StatusOr<std::string> DescribePointPoses(const PointFiles& files, const std::vector<LegsRow>& rows) {
  StatusOr<LoadedPoints> loaded = LoadPoints(files);
  if (!loaded.ok()) return loaded.status();
  if (StatusOr<std::map<std::string, const PointSet*>> sets = SetsOfRows(*loaded, files.points, rows); !sets.ok())
    return sets.status();
  return std::to_string(rows.size()) + " point sets, " + std::to_string(loaded->reflectors.size()) + " reflectors" +
         (loaded->estimated ? " (estimated from the poses)" : "");
}

StatusOr<PointFiles> SessionPointFiles(const std::string& dir, const SessionConfig& config, bool with_noise_factor) {
  PointFiles files{ResolveSessionFile(dir, config.points),
                   config.reflectors.empty() ? "" : ResolveSessionFile(dir, config.reflectors), config.point_sigma};
  if (!with_noise_factor) return files;
  StatusOr<double> factor = SessionNoiseFactor(dir);
  if (!factor.ok()) return factor.status();
  files.noise_factor = *factor;
  return files;
}

StatusOr<PointPoseReview> ReviewPointPoses(const PointFiles& files, const std::vector<std::string>& poses) {
  StatusOr<LoadedPoints> loaded = LoadPoints(files);
  if (!loaded.ok()) return loaded.status();
  std::map<std::string, const PointSet*> by_name;
  for (const PointSet& set : loaded->sets) by_name[set.pose] = &set;
  PointPoseReview review;
  review.reflectors = static_cast<int>(loaded->reflectors.size());
  review.reflectors_estimated = loaded->estimated;
  const std::string file = fs::path(files.points).filename().string();
  for (const std::string& pose : poses) {
    PointPoseFit row{pose, "no_points", "no points in " + file, 0, 0};
    const auto found = by_name.find(pose);
    if (found != by_name.end()) {
      row.points = static_cast<int>(found->second->points.size());
      const StatusOr<PointFit> fit = FitPointPose(loaded->reflectors, found->second->points);
      row.status = fit.ok() ? "ok" : "bad_points";
      row.message = fit.ok() ? "" : fit.status().message();
      row.rms = fit.ok() ? fit->rms : 0;
    }
    review.fitted += row.status == "ok";
    review.poses.push_back(row);
  }
  return review;
}

StatusOr<double> SessionNoiseFactor(const std::string& session_dir) {
  const std::string record = SessionPaths(session_dir).noise_check;
  std::error_code error;
  if (!fs::exists(fs::symlink_status(record, error))) return 1.0;
  StatusOr<std::string> text = ReadFileToString(record, kMaxYamlBytes);
  if (!text.ok()) return text.status();
  StatusOr<nlohmann::json> json = ParseJsonText(*text, record);
  if (!json.ok()) return json.status();
  if (!json->is_object()) return Status::BadInput(record + ": not a JSON object");
  JsonFields fields(*json, record);
  const double ratio = fields.Number("ratio");
  if (!fields.status().ok()) return fields.status();
  if (!(ratio > 0 && ratio < 1e6)) return Status::BadInput(record + ": ratio: not a positive number");
  return std::max(1.0, ratio);
}

}  // namespace hexcal::workflow

#include "workflow/noise_check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "session/session_models.h"
#include "vision/measure.h"
#include "workflow/point_session.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

StatusOr<Repeatability> PointRepeatability(const SessionConfig& config, const std::string& input) {
  StatusOr<PointSets> sets = LoadPointFile(input, config.point_sigma);
  if (!sets.ok()) return sets.status();
  StatusOr<Repeatability> figures = MeasurePointRepeatability(*sets);
  if (!figures.ok()) return Status::BadInput(input + ": " + figures.status().message());
  return figures;
}

// The board poses of k images of one pose: their scatter about the mean
// against the mean of their covariances, coordinate by coordinate (angles
// unwrapped about the first image's).
Repeatability BoardPoseScatter(const std::vector<Vector6d>& poses, const std::vector<Matrix6d>& covariances,
                               int corners) {
  const size_t k = poses.size();
  Vector6d mean = Vector6d::Zero();
  std::vector<Vector6d> unwrapped;
  for (const Vector6d& pose : poses) {
    Vector6d v = pose;
    for (int c = 3; c < 6; ++c) v[c] = poses[0][c] + std::remainder(v[c] - poses[0][c], 360.0);
    unwrapped.push_back(v);
    mean += v / static_cast<double>(k);
  }
  Vector6d scatter = Vector6d::Zero(), predicted = Vector6d::Zero();
  for (size_t j = 0; j < k; ++j) {
    scatter += (unwrapped[j] - mean).cwiseAbs2() / static_cast<double>(k - 1);
    predicted += covariances[j].diagonal() / static_cast<double>(k);
  }
  Repeatability figures;
  figures.repeats = static_cast<int>(k);
  figures.points = corners;
  figures.degrees_of_freedom = 6 * static_cast<int>(k - 1);
  figures.measured_sigma = std::sqrt(scatter.head<3>().mean());
  figures.declared_sigma = std::sqrt(predicted.head<3>().mean());
  figures.ratio = std::sqrt(scatter.cwiseQuotient(predicted).mean());
  return figures;
}

StatusOr<Repeatability> CameraRepeatability(const std::string& dir, const SessionConfig& config,
                                            const std::string& input, const JobHooks& hooks, std::string* unit) {
  StatusOr<Camera> camera = LoadCamera(ResolveSessionFile(dir, config.camera));
  if (!camera.ok()) return camera.status();
  StatusOr<Target> target = LoadTarget(ResolveSessionFile(dir, config.target));
  if (!target.ok()) return target.status();
  StatusOr<std::vector<std::string>> files = ListImages(input);
  if (!files.ok()) return files.status();
  StatusOr<std::vector<ImageMeasurement>> measured = MeasureImages(*files, *camera, *target, MeasureOptions{}, hooks);
  if (!measured.ok()) return measured.status();
  std::vector<Vector6d> poses;
  std::vector<Matrix6d> covariances;
  int corners = 0;
  for (const ImageMeasurement& m : *measured) {
    if (m.pose.status != PoseStatus::kOk) {
      hooks.Note("warning: " + m.file + ": " + m.pose.message + "; left out");
      continue;
    }
    poses.push_back(VectorFromPose(m.pose.camera_from_target, EulerConvention::kXYZ));
    covariances.push_back(m.pose.covariance_vector);
    corners = std::max(corners, m.pose.num_corners);
  }
  if (poses.size() < 3)
    return Status::BadInput(input + ": " + std::to_string(poses.size()) +
                            " images with a board pose: the repeatability needs 3 or more of one pose");
  *unit = LengthUnitName(target->length_unit);
  return BoardPoseScatter(poses, covariances, corners);
}

std::string Judge(double ratio) {
  if (ratio > 1 + kNoiseRatioTolerance) return "optimistic";
  if (ratio < 1 - kNoiseRatioTolerance) return "pessimistic";
  return "good";
}

}  // namespace

StatusOr<NoiseCheck> CheckSessionNoise(const NoiseCheckRequest& request, const JobHooks& hooks) {
  const std::string& dir = request.session;
  StatusOr<SessionConfig> config = LoadSessionConfig(dir);
  if (!config.ok()) return config.status();
  StatusOr<SessionLock> lock = SessionLock::Acquire(dir, request.wait);  // writes noise_check.json
  if (!lock.ok()) return lock.status();
  NoiseCheck check;
  check.instrument = config->instrument;
  StatusOr<Repeatability> figures = Status::BadInput("");
  if (config->instrument == Instrument::kPoints) {
    StatusOr<Robot> robot = LoadSessionRobot(dir, *config);
    if (!robot.ok()) return robot.status();
    check.unit = LengthUnitName(robot->length_unit);
    figures = PointRepeatability(*config, request.input);
  } else {
    figures = CameraRepeatability(dir, *config, request.input, hooks, &check.unit);
  }
  if (!figures.ok()) return figures.status();
  check.figures = *figures;
  check.judgement = Judge(figures->ratio);
  const std::string record = SessionPaths(dir).noise_check;
  if (Status s = WriteFileAtomically(record, ToJson(check).dump(2) + "\n"); !s.ok()) return s;
  return check;
}

nlohmann::json ToJson(const NoiseCheck& check) {
  const Repeatability& r = check.figures;
  return {{"format", 1},
          {"instrument", InstrumentName(check.instrument)},
          {"repeats", r.repeats},
          {"points", r.points},
          {"degrees_of_freedom", r.degrees_of_freedom},
          {"measured_sigma", r.measured_sigma},
          {"declared_sigma", r.declared_sigma},
          {"unit", check.unit},
          {"ratio", r.ratio},
          {"judgement", check.judgement}};
}

std::string FormatNoiseCheck(const NoiseCheck& check) {
  const Repeatability& r = check.figures;
  std::ostringstream out;
  const bool points = check.instrument == Instrument::kPoints;
  out << (points ? "repeatability: " + std::to_string(r.repeats) + " point sets of " + std::to_string(r.points) +
                       " reflectors"
                 : "repeatability: " + std::to_string(r.repeats) + " images of the board") << " ("
      << r.degrees_of_freedom << " degrees of freedom)\n"
      << "  measured sigma " << FormatSignificant(r.measured_sigma) << " " << check.unit << ", declared "
      << FormatSignificant(r.declared_sigma) << " " << check.unit
      << (points ? " (each coordinate of a point)" : " (each position coordinate of the board pose)") << "\n"
      << "  ratio measured/declared " << FormatSignificant(r.ratio) << (points ? "" : " (over the six coordinates)")
      << ": " << check.judgement;
  if (check.judgement == "good") out << " (within " << kNoiseRatioTolerance * 100 << " %)\n";
  else if (check.judgement == "optimistic")
    out << ": the noise is larger than declared; "
        << (points ? "the calibration scales the points' covariances by the ratio\n"
                   : "the calibration's uncertainties may be too small: check the focus and lighting\n");
  else
    out << ": the noise is smaller than declared; the uncertainties are conservative\n";
  return out.str();
}

}  // namespace hexcal::workflow

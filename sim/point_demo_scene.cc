#include "sim/point_demo_scene.h"

#include <cstdio>
#include <filesystem>
#include <random>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/registration.h"
#include "core/session.h"
#include "sim/sim_world.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPointsFile = "points.txt";
constexpr const char* kReflectorFile = "reflectors.csv";

std::string PoseName(size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "pose_%04zu", index);
  return name;
}

// One line of SpatialAnalyzer's ASCII export: collection, group (the pose),
// target (the reflector), x, y, z.
std::string PointLine(const std::string& pose, const NamedPoint& point) {
  std::string line = "tracker " + pose + " " + point.name;
  for (int k = 0; k < 3; ++k) line += " " + FormatNumber(point.position[k]);
  return line + "\n";
}

Status WriteReflectorFile(const std::string& path, const std::vector<NamedPoint>& reflectors) {
  std::vector<std::vector<std::string>> rows;
  for (const NamedPoint& r : reflectors)
    rows.push_back({r.name, FormatNumber(r.position.x()), FormatNumber(r.position.y()), FormatNumber(r.position.z())});
  return WriteCsv(path, {"point", "x", "y", "z"}, rows);
}

SessionConfig PointSessionConfig(const DemoScene& scene, const PointDemoOptions& options,
                                 const std::string& robot_name) {
  SessionConfig config;
  config.robot = robot_name;
  config.instrument = Instrument::kPoints;
  config.points = kPointsFile;
  if (options.reflector_file) config.reflectors = kReflectorFile;
  config.point_sigma = options.sigma;
  config.noise = scene.noise;  // its pose half-widths are replaced by the fits' at calibration
  return config;
}

}  // namespace

std::vector<NamedPoint> DemoReflectors(const DemoScene& scene) {
  double radius = 0;
  for (const Leg& leg : scene.nominal.legs) radius = std::max(radius, leg.b_in_platform.head<2>().norm());
  const std::vector<NamedPoint> on_platform = {{"R1", {radius, 0, 0.1 * radius}},
                                               {"R2", {-0.5 * radius, 0.85 * radius, 0}},
                                               {"R3", {-0.5 * radius, -0.85 * radius, 0.2 * radius}},
                                               {"R4", {0, 0.1 * radius, 0.4 * radius}}};
  // In the reflector frame, which the scene places at platform_from_target.
  const Pose reflectors_from_platform = Inverse(scene.platform_from_target);
  std::vector<NamedPoint> reflectors;
  for (const NamedPoint& r : on_platform)
    reflectors.push_back({r.name, reflectors_from_platform.rotation * r.position + reflectors_from_platform.position, 0});
  return reflectors;
}

std::vector<NamedPoint> ReflectorsInTracker(const DemoScene& scene, const Pose& base_from_platform) {
  // tracker_from_reflectors = X⁻¹ · base_from_platform · Y
  const Pose seen_from =
      Compose(Compose(Inverse(scene.base_from_camera), base_from_platform), scene.platform_from_target);
  std::vector<NamedPoint> seen;
  for (const NamedPoint& r : DemoReflectors(scene))
    seen.push_back({r.name, seen_from.rotation * r.position + seen_from.position, 0});
  return seen;
}

PointSet SimTrackerMeasure(SimWorld& world, double sigma, const std::string& pose, uint64_t draw) {
  std::mt19937_64 rng(world.scene().seed * 104729 + draw);
  std::normal_distribution<double> point_noise(0, sigma);
  PointSet measured{pose, {}};
  for (NamedPoint seen : ReflectorsInTracker(world.scene(), world.ActualPose())) {
    for (int k = 0; k < 3; ++k) seen.position[k] += point_noise(rng);
    seen.sigma = sigma;
    measured.points.push_back(seen);
  }
  return measured;
}

Status RecordPointDemoSession(const DemoScene& scene, const PointDemoOptions& options, const std::string& robot_name,
                              const std::vector<Vector6d>& planned, const std::vector<Vector6d>& held_out,
                              const std::string& dir) {
  if (Status s = InitSession(dir, PointSessionConfig(scene, options, robot_name)); !s.ok()) return s;
  if (Status s = WriteSceneTruth(scene, dir); !s.ok()) return s;
  std::vector<Vector6d> poses = planned;
  poses.insert(poses.end(), held_out.begin(), held_out.end());
  std::mt19937_64 rng(scene.seed * 7919 + 17);
  std::uniform_real_distribution<double> unit_noise(-1, 1);
  std::normal_distribution<double> point_noise(0, options.sigma);
  std::vector<std::vector<std::string>> legs_rows;
  std::string points = "// SpatialAnalyzer ASCII export (hexcal demo --instrument points): collection group target x y z\n";
  for (size_t j = 0; j < poses.size(); ++j) {
    const Pose platform = scene.truth.PoseFromVector(poses[j]);
    const LegReadings readings = InverseKinematics(scene.truth, platform);
    std::vector<std::string> row = {PoseName(j)};
    for (int i = 0; i < kNumLegs; ++i) row.push_back(FormatNumber(readings[i] + scene.noise.leg * unit_noise(rng)));
    row.push_back(j < planned.size() ? "0" : "1");
    // The pose each row was commanded to, as the Acquire step records it: the
    // GUI's checklist then shows the plan's poses recorded (plan_captures.h).
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(poses[j][k]));
    legs_rows.push_back(row);
    for (const NamedPoint& seen : ReflectorsInTracker(scene, platform)) {
      const Eigen::Vector3d noise(point_noise(rng), point_noise(rng), point_noise(rng));
      points += PointLine(PoseName(j), {seen.name, seen.position + noise, 0});
    }
  }
  if (Status s = WriteFileAtomically((fs::path(dir) / kPointsFile).string(), points); !s.ok()) return s;
  if (options.reflector_file) {
    if (Status s = WriteReflectorFile((fs::path(dir) / kReflectorFile).string(), DemoReflectors(scene)); !s.ok()) return s;
  }
  std::vector<std::string> header = {"pose", "L1", "L2", "L3", "L4", "L5", "L6", "holdout"};
  header.insert(header.end(), std::begin(kCommandedColumns), std::end(kCommandedColumns));
  return WriteCsv(SessionPaths(dir).legs, header, legs_rows);
}

}  // namespace hexcal::workflow

#include "sim/demo_scene.h"

#include <cstdio>
#include <filesystem>
#include <random>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/parallel.h"
#include "core/registration.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "core/simulation.h"
#include "vision/image_codecs.h"
#include "vision/renderer.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;

std::string ImageName(size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "view_%04zu.png", index);
  return name;
}

std::string FramesYaml(const DemoScene& scene) {
  const auto line = [](const char* key, const Pose& pose) {
    const Vector6d v = VectorFromPose(pose, EulerConvention::kXYZ);
    std::string text = std::string(key) + ": [";
    for (int k = 0; k < 6; ++k) text += FormatNumber(v[k]) + (k < 5 ? ", " : "]\n");
    return text;
  };
  return "# The true frames of the demo (robot unit, degrees, Euler xyz), hidden from the calibration.\n" +
         line("base_from_camera", scene.base_from_camera) + line("platform_from_target", scene.platform_from_target);
}

}  // namespace

DemoScene MakeDemoScene(const Robot& nominal, const Camera& camera, const Target& target,
                        const DemoSceneOptions& options) {
  const double unit = MetresPerUnit(nominal.length_unit);
  DemoScene scene{nominal, PerturbedRobot(nominal, options.perturb_m / unit, options.seed), camera, target,
                  Pose{}, Pose{}, NoiseModel{}, MeasurementConstraints{}, options.seed};
  scene.noise.position = options.position_noise_m / unit;
  scene.noise.angle_deg = options.angle_noise_deg;
  scene.noise.leg = options.leg_noise_m / unit;

  // The camera looks down (+z of the camera along -z of the base) from above
  // the centre of the sampling box, a little off-centre and tilted, as mounted
  // by hand; the target lies on the platform, centred, turned by 5 degrees.
  const Vector6d centre = WorkspaceCentre(nominal);
  Vector6d camera_vector;
  camera_vector << 0.015 / unit, -0.02 / unit, centre[2] + options.camera_distance_m / unit, 180.0, 2.0, -4.0;
  scene.base_from_camera = PoseFromVector(camera_vector, EulerConvention::kXYZ);

  const double target_scale = MetresPerUnit(target.length_unit) / unit;
  const Eigen::Vector2d middle = target.TagsMin() + 0.5 * Eigen::Vector2d(target.Width(), target.Height());
  const Eigen::Vector3d target_centre(middle.x() * target_scale, middle.y() * target_scale, 0);
  Vector6d turn;
  turn << 0, 0, 0.005 / unit, 0, 0, 5.0;
  Pose to_centre;
  to_centre.position = -target_centre;
  scene.platform_from_target = Compose(PoseFromVector(turn, EulerConvention::kXYZ), to_centre);

  // The planner keeps the target's centre well inside the image, so that the
  // whole board is seen: the field of view less the board's half-size at the
  // camera distance, and no view flatter than 50 degrees.
  Pose centre_of_target;
  centre_of_target.position = target_centre;
  scene.view.base_from_camera = scene.base_from_camera;
  scene.view.platform_from_target = Compose(scene.platform_from_target, centre_of_target);
  const double board_half_deg = RadToDeg(std::atan(target_centre.x() * unit / options.camera_distance_m));
  scene.view.half_fov_x_deg =
      RadToDeg(std::atan(camera.width / 2.0 / camera.fx)) - board_half_deg - 2;
  scene.view.half_fov_y_deg =
      RadToDeg(std::atan(camera.height / 2.0 / camera.fy)) - board_half_deg - 2;
  scene.view.max_view_angle_deg = 50;
  return scene;
}

Status WriteSceneTruth(const DemoScene& scene, const std::string& dir) {
  const fs::path truth_dir = fs::path(dir) / "truth";
  if (Status s = CreateFolders(truth_dir.string()); !s.ok()) return s;
  if (Status s = SaveRobot(scene.truth, (truth_dir / "robot.yaml").string()); !s.ok()) return s;
  return WriteFileAtomically((truth_dir / "frames.yaml").string(), FramesYaml(scene));
}

Status RecordDemoSession(const DemoScene& scene, const std::string& robot_name, const std::string& camera_name,
                         const std::vector<Vector6d>& planned,
                         const std::vector<Vector6d>& held_out, const std::string& dir,
                         const std::function<void(int, int)>& progress) {
  SessionConfig config;
  config.robot = robot_name;
  config.camera = camera_name;
  config.target = kDefaultTargetName;
  config.noise = scene.noise;
  if (Status s = InitSession(dir, config); !s.ok()) return s;
  const SessionPaths paths(dir);
  if (Status s = WriteSceneTruth(scene, dir); !s.ok()) return s;

  std::vector<Vector6d> poses = planned;
  poses.insert(poses.end(), held_out.begin(), held_out.end());
  // Readings: the true robot's IK at the pose plus uniform noise of ±noise.leg.
  std::mt19937_64 rng(scene.seed * 7919 + 17);
  std::uniform_real_distribution<double> unit_noise(-1, 1);
  std::vector<std::vector<std::string>> legs_rows;
  for (size_t j = 0; j < poses.size(); ++j) {
    const LegReadings readings = InverseKinematics(scene.truth, scene.truth.PoseFromVector(poses[j]));
    std::vector<std::string> row = {ImageName(j)};
    for (int i = 0; i < kNumLegs; ++i) row.push_back(FormatNumber(readings[i] + scene.noise.leg * unit_noise(rng)));
    row.push_back(j < planned.size() ? "0" : "1");
    legs_rows.push_back(row);
  }

  // Images: camera_from_target = X⁻¹ · base_from_platform · Y, in the target's unit.
  RenderOptions render;
  render.seed = scene.seed;
  const Renderer renderer(scene.camera, scene.target, render);
  const double to_target_unit = MetresPerUnit(scene.nominal.length_unit) / MetresPerUnit(scene.target.length_unit);
  std::vector<Status> written(poses.size());
  ParallelFor(
      static_cast<int>(poses.size()), 2,
      [&](int index, int) {
        const size_t j = static_cast<size_t>(index);
        Pose camera_from_target =
            CameraFromTarget(scene.base_from_camera, scene.truth.PoseFromVector(poses[j]), scene.platform_from_target);
        camera_from_target.position *= to_target_unit;
        const RenderedView view = renderer.Render(camera_from_target, j);
        StatusOr<std::string> png = EncodePng(view.image);
        written[j] = png.ok() ? WriteFileAtomically((fs::path(paths.images) / ImageName(j)).string(), *png)
                              : png.status();
      },
      {progress});
  for (const Status& s : written)
    if (!s.ok()) return s;
  return WriteCsv(paths.legs, {"image", "L1", "L2", "L3", "L4", "L5", "L6", "holdout"}, legs_rows);
}

}  // namespace hexcal::workflow

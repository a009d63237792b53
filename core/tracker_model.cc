#include "core/tracker_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/constraints.h"
#include "core/point_fit.h"

namespace hexcal {

const OptionTable<TrackerSettings>& TrackerSettingsOptions() {
  static const OptionTable<TrackerSettings> table = [] {
    OptionTable<TrackerSettings> t;
    OptionSpec<TrackerSettings> law;
    law.key = "sigma_law";
    law.label = "Tracker: σ law";
    law.type = OptionType::kChoice;
    law.choices = {"constant", "linear"};
    law.help = "constant: point_sigma at any distance; linear: sigma0 + sigma_per_distance × distance (needs position)";
    law.get_choice = [](const TrackerSettings& s) {
      return std::string(s.sigma_law == PointSigmaLaw::kLinear ? "linear" : "constant");
    };
    law.set_choice = [](TrackerSettings& s, const std::string& v) {
      s.sigma_law = v == "linear" ? PointSigmaLaw::kLinear : PointSigmaLaw::kConstant;
    };
    t.push_back(std::move(law));
    t.push_back(NumberOption<TrackerSettings>(
        "sigma0", "Tracker: σ at distance 0", OptionType::kNumber, "robot unit", 0, 1e6,
        "σ of each coordinate at distance 0 (law linear; a tracker's 15 µm)",
        [](TrackerSettings& s) -> double& { return s.sigma0; }));
    t.push_back(NumberOption<TrackerSettings>(
        "sigma_per_distance", "Tracker: σ per distance", OptionType::kNumber, "unit per unit", 0, 1e-3,
        "growth of σ with the distance to the tracker (law linear; 6 µm/m is 0.000006)",
        [](TrackerSettings& s) -> double& { return s.sigma_per_distance; }));
    t.push_back(NumberOption<TrackerSettings>(
        "acceptance_deg", "Tracker: acceptance half-angle", OptionType::kNumber, "deg", 1, 90,
        "a reflector is seen within this angle of its normal (an SMR's ±30°)",
        [](TrackerSettings& s) -> double& { return s.acceptance_deg; }));
    t.push_back(NumberOption<TrackerSettings>(
        "leg_radius", "Tracker: leg radius", OptionType::kNumber, "robot unit", 0, 1e6,
        "the legs' radius: a sight line closer to a leg's axis is blocked (0: legs as lines)",
        [](TrackerSettings& s) -> double& { return s.leg_radius; }));
    return t;
  }();
  return table;
}

namespace {

bool Refuse(std::string* error, const std::string& why) {
  *error = why;
  return false;
}

}  // namespace

bool TrackerSettings::IsValid(std::string* error) const {
  for (const OptionSpec<TrackerSettings>& spec : TrackerSettingsOptions()) {
    if (spec.type != OptionType::kNumber) continue;
    const Status in_range = CheckOptionRange(spec, spec.get_number(*this), "tracker." + spec.key);
    if (!in_range.ok()) return Refuse(error, in_range.message());
  }
  if (position && !position->allFinite()) return Refuse(error, "tracker.position: expected 3 finite numbers");
  if (!reflector_normal.allFinite() || !(reflector_normal.norm() > 1e-12))
    return Refuse(error, "tracker.reflector_normal: expected a non-zero direction [x, y, z]");
  if (sigma_law == PointSigmaLaw::kLinear) {
    if (!position) return Refuse(error, "tracker.sigma_law: linear needs tracker.position (the distance is from it)");
    if (!(sigma0 > 0)) return Refuse(error, "tracker.sigma0: law linear needs a positive sigma0");
  }
  return true;
}

StatusOr<TrackerModel> MakeTrackerModel(const Robot& robot, const std::vector<Eigen::Vector3d>& reflectors,
                                        double point_sigma, const TrackerSettings& settings,
                                        const Pose& platform_from_reflectors) {
  std::string error;
  if (!settings.IsValid(&error)) return Status::BadInput(error);
  if (!(point_sigma > 0 && point_sigma < 1e6))
    return Status::BadInput("point_sigma: expected a positive length in the robot's unit");
  TrackerModel model;
  model.point_sigma = point_sigma;
  model.settings = settings;
  std::vector<NamedPoint> named;
  for (const Eigen::Vector3d& r : reflectors) {
    model.reflectors.push_back(platform_from_reflectors * r);
    named.push_back({"R" + std::to_string(named.size() + 1), model.reflectors.back(), 0});
  }
  // The fit's own checks: 3 or more, not on one line.
  StatusOr<std::pair<double, double>> sigma = PoseSigmaOfReflectors(named, point_sigma);
  if (!sigma.ok()) return Status::BadInput("reflectors: " + sigma.status().message());
  model.normal_in_platform = platform_from_reflectors.rotation * settings.reflector_normal.normalized();
  for (const Leg& leg : robot.legs) model.disc_centre += leg.b_in_platform / kNumLegs;
  for (const Leg& leg : robot.legs)
    model.disc_radius = std::max(model.disc_radius, (leg.b_in_platform - model.disc_centre).head<2>().norm());
  return model;
}

double PointSigmaAt(const TrackerModel& tracker, double distance) {
  if (tracker.settings.sigma_law == PointSigmaLaw::kConstant) return tracker.point_sigma;
  return tracker.settings.sigma0 + tracker.settings.sigma_per_distance * distance;
}

std::vector<double> ReflectorSigmas(const TrackerModel& tracker, const Pose& base_from_platform) {
  std::vector<double> sigmas;
  for (const Eigen::Vector3d& r : tracker.reflectors) {
    const double distance =
        tracker.settings.position ? (*tracker.settings.position - base_from_platform * r).norm() : 0.0;
    sigmas.push_back(PointSigmaAt(tracker, distance));
  }
  return sigmas;
}

Matrix6d TrackerPoseCovariance(const TrackerModel& tracker, const Robot& robot, const Pose& base_from_platform) {
  // The tracker's frame is the base's up to a rigid motion, and each point's
  // noise is isotropic: fitting base_from_platform to the reflectors seen in
  // the base frame has the registered fit's covariance.
  return PointPoseCovariance(base_from_platform, tracker.reflectors, ReflectorSigmas(tracker, base_from_platform),
                             robot.euler);
}

std::array<double, 3> ReflectorSightMargins(const SightScene& scene, const Eigen::Vector3d& reflector,
                                            const Eigen::Vector3d& normal) {
  const Eigen::Vector3d to_tracker = scene.tracker - reflector;
  const double angle = RadToDeg(std::atan2(normal.cross(to_tracker).norm(), normal.dot(to_tracker)));
  // The disc blocks when the sight line crosses its plane (strictly: a
  // reflector on the plane is on the side it faces) inside its radius.
  const double s0 = scene.disc_normal.dot(reflector - scene.disc_centre);
  const double s1 = scene.disc_normal.dot(scene.tracker - scene.disc_centre);
  double disc = std::min(std::abs(s0), std::abs(s1));
  if ((s0 > 0 && s1 < 0) || (s0 < 0 && s1 > 0)) {
    const Eigen::Vector3d crossing = reflector + s0 / (s0 - s1) * to_tracker;
    disc = (crossing - scene.disc_centre).norm() - scene.disc_radius;
  }
  double legs = std::numeric_limits<double>::infinity();
  for (const auto& [bottom, top] : scene.legs)
    legs = std::min(legs, SegmentDistance(reflector, scene.tracker, bottom, top) - scene.leg_radius);
  return {scene.acceptance_deg - angle, disc, legs};
}

std::vector<double> LineOfSightMargins(const TrackerModel& tracker, const Robot& robot, const Pose& base_from_platform) {
  if (!tracker.settings.position) return {};
  SightScene scene;
  scene.tracker = *tracker.settings.position;
  scene.acceptance_deg = tracker.settings.acceptance_deg;
  scene.disc_centre = base_from_platform * tracker.disc_centre;
  scene.disc_normal = base_from_platform.rotation.col(2);
  scene.disc_radius = tracker.disc_radius;
  for (const Leg& leg : robot.legs) scene.legs.emplace_back(leg.a_in_base, base_from_platform * leg.b_in_platform);
  scene.leg_radius = tracker.settings.leg_radius;
  const Eigen::Vector3d normal = base_from_platform.rotation * tracker.normal_in_platform;
  std::vector<double> margins;
  for (const Eigen::Vector3d& r : tracker.reflectors)
    for (double m : ReflectorSightMargins(scene, base_from_platform * r, normal)) margins.push_back(m);
  return margins;
}

}  // namespace hexcal

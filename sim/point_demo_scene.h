// The laser-tracker variant of `hexcal demo` (issue 38, docs/calibration.md,
// "Point measurements"): the demo scene's hidden true robot and frames
// (demo_scene.h), with a tracker where the camera was and reflectors where the
// board was. At each pose the tracker measures every reflector with N(0, σ²)
// noise on each coordinate; the session holds the points in SpatialAnalyzer's
// ASCII layout, the reflectors' positions as a CMM would give them, and
// legs.csv with a `pose` column and each row's commanded pose (as the GUI's
// Acquire step records it).
//
//   Status s = RecordPointDemoSession(scene, {0.002}, "inria-left-hand", planned, held_out, "demo-points");
#pragma once

#include <string>
#include <vector>

#include "core/point_file.h"
#include "core/point_fit.h"
#include "sim/demo_scene.h"

namespace hexcal::workflow {

class SimWorld;

struct PointDemoOptions {
  double sigma = 0;  // of each coordinate, robot unit
  bool reflector_file = true;  // false: the session estimates the reflectors from the poses
};

// Four reflectors on the platform, not coplanar, spread over its anchors'
// radius about its centre, in the reflector frame (the scene's
// platform_from_target).
std::vector<NamedPoint> DemoReflectors(const DemoScene& scene);

// Where the tracker sees the reflectors (DemoReflectors) with the platform at
// `base_from_platform` (the true robot's): in the tracker frame, no noise.
std::vector<NamedPoint> ReflectorsInTracker(const DemoScene& scene, const Pose& base_from_platform);

// The sim tracker beside the sim controller (the GUI's Acquire step of a
// points session): the reflectors where the sim world's platform really is,
// each coordinate with N(0, σ²) noise (σ > 0, robot unit; each point carries
// it), drawn from the scene's seed and `draw` (one per measurement).
PointSet SimTrackerMeasure(SimWorld& world, double sigma, const std::string& pose, uint64_t draw);

// Initialises the points session DIR and records `planned` then `held_out`
// (holdout 1): legs.csv, points.txt, reflectors.csv and the hidden truth.
Status RecordPointDemoSession(const DemoScene& scene, const PointDemoOptions& options, const std::string& robot_name,
                              const std::vector<Vector6d>& planned, const std::vector<Vector6d>& held_out,
                              const std::string& dir);

}  // namespace hexcal::workflow

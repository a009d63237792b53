// make_session OUT: the GUI tests' sessions, made with the workflow layer as
// the GUI's "Open demo session" makes them (a virtual robot and camera;
// docs/session.md): 12 planned and 4 held-out images.
//   OUT/calibrated/ the demo session: planned, measured, calibrated
//   OUT/rendered/   its 16 images, not yet in a session (the flow test loads them)
//   OUT/session/    session.yaml and legs.csv of the same run, images/ empty
//   OUT/points/     a points session (a simulated laser tracker, issue 38):
//                   12 planned and 4 held-out poses, its reflector file, calibrated
#include <filesystem>
#include <iostream>

#include "core/session.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/demo.h"

namespace fs = std::filesystem;
using namespace hexcal;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_session OUT\n";
    return 2;
  }
  const fs::path out = argv[1];
  fs::remove_all(out);
  fs::create_directories(out);
  workflow::DemoRequest demo;
  demo.out = (out / "calibrated").string();
  demo.poses = 12;
  demo.holdout = 4;
  demo.seed = 2;
  StatusOr<workflow::DemoResult> made = workflow::RunDemo(demo);
  if (!made.ok()) {
    std::cerr << "make_session: " << made.status().message() << "\n";
    return 1;
  }
  fs::copy(out / "calibrated" / "images", out / "rendered", fs::copy_options::recursive);
  SessionConfig config;
  config.robot = "inria-left-hand";
  config.camera = kSimulatedCameraName;
  config.target = kDefaultTargetName;
  config.noise.position = 0.005;
  config.noise.angle_deg = 0.02;
  config.noise.leg = 0.001;
  if (Status s = InitSession((out / "session").string(), config); !s.ok()) {
    std::cerr << "make_session: " << s.message() << "\n";
    return 1;
  }
  fs::copy_file(out / "calibrated" / "legs.csv", out / "session" / "legs.csv");
  workflow::DemoRequest points = demo;
  points.out = (out / "points").string();
  points.instrument = Instrument::kPoints;
  points.quick_plan = true;  // a calibrated session is wanted, not the demo's figures
  points.seed = 1;           // the GUI's sim world's: its Acquire step connects to the session's truth
  if (StatusOr<workflow::DemoResult> made_points = workflow::RunDemo(points); !made_points.ok()) {
    std::cerr << "make_session: " << made_points.status().message() << "\n";
    return 1;
  }
  return 0;
}

// `hexcal demo` and the GUI's "Open demo session": the whole calibration
// flow on a virtual robot and camera (docs/session.md, "hexcal demo"):
//  1. plan N poses with IOOPS (O1 primary, O4 secondary, Tabu 4) among random
//     and boundary candidates the camera can see, or with `random_poses` draw
//     N random feasible poses the camera sees (the paper's section 8 records
//     64 such poses for `hexcal study`, study_step.h);
//  2. record a session folder: a hidden true robot (nominal ± 0.5 mm on every
//     parameter) at unknown camera and target frames, an image rendered at
//     every pose (demo_scene.h) and noisy leg readings, plus random held-out
//     poses (none with holdout 0);
//  3. measure → register → calibrate → validate (CalibrateSession);
//     with `instrument` kPoints, a laser tracker's reflector points stand in
//     for the camera's images (point_demo_scene.h);
//  4. compare the calibrated parameters with the truth in the registered
//     frames (the gauge, docs/session.md), and write results/report.html.
//
//   StatusOr<DemoResult> demo = RunDemo({.out = "demo", .force = true}, hooks);
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/design_criteria.h"
#include "core/job_hooks.h"
#include "core/observability.h"
#include "core/session.h"
#include "core/status.h"
#include "report/calibration_verdict.h"
#include "session/calibration_report.h"

namespace hexcal::workflow {

struct DemoRequest {
  std::string robot = "inria-left-hand";  // robot file or preset name
  std::string out = "hexcal-demo";        // the session folder to write
  int poses = 24;                         // planned calibration poses
  int holdout = 8;                        // random poses kept out to validate (0: none, no validation)
  uint64_t seed = 1;                      // of the truth, the candidates and the noise
  bool force = false;                     // replace an earlier demo in `out`
  // For tests that need a calibrated session, not the demo's figures: random
  // candidates only (no boundary poses, whose FK is most of the plan's time)
  // and O1 alone, no secondary criterion. Under the sanitizers the full plan
  // is about a minute.
  bool quick_plan = false;
  // Record `poses` random feasible poses the camera sees instead of an IOOPS
  // plan: the paper's section 8 measures 64 such poses and studies subsets of
  // them (`hexcal study`).
  bool random_poses = false;
  // false: calibrate with `calibrate --session --two-stage`; true, the
  // default: from pixels, the focal length estimated (with kPoints: from the
  // points, the reflectors estimated).
  bool from_pixels = true;
  // The camera file given to the calibration has fx and fy off by this many
  // percent (the renderer keeps the true ones): a focal error for the
  // calibration to live with, or, from pixels, to estimate.
  double focal_error_percent = 0;
  // kPoints: a laser tracker measures 4 reflectors on the platform instead of
  // the camera seeing the board (point_demo_scene.h), with this σ on each
  // coordinate, millimetres.
  Instrument instrument = Instrument::kCamera;
  double point_sigma_mm = 0.02;

  // The ranges of DemoOptions() (workflow/demo_options.h); an error names
  // the option by its key (Status::option()).
  Status Check() const;
};

struct ParameterError {
  int leg = 0;
  std::string name;
  double error = 0;             // |calibrated − truth in the gauge|, robot unit
  std::optional<double> sigma;  // the calibration's σ
};

struct DemoResult {
  std::string robot, length_unit, session;
  int poses = 0, held_out = 0, usable_images = 0;
  ObservabilityIndices random_indices, plan_indices;  // the random start set and the plan
  int plan_candidates = 0, plan_iterations = 0;       // 0 with random_poses
  bool random_poses = false;                          // the poses are random, not planned
  bool from_pixels = false;                           // calibrated from pixels
  bool from_points = false;                           // calibrated from the points (points sessions)
  double focal_error_percent = 0;                     // of the calibration's camera file
  Instrument instrument = Instrument::kCamera;        // what measured the poses
  double error_mean = 0, error_max = 0;                  // calibrated − truth
  double nominal_error_mean = 0, nominal_error_max = 0;  // nominal − truth
  double within_3sigma = 0;                              // fraction of the parameters with a σ
  int with_sigma = 0;
  std::vector<ParameterError> parameters;
  CalibrationReport calibration;  // results/report.json
  Verdict verdict;                // on `calibration`, with the truth (calibration_verdict.h)
  std::string report;             // results/report.html
  double seconds = 0;
};

// Progress: hooks.stage gets "[k/5] ..." step descriptions.
StatusOr<DemoResult> RunDemo(const DemoRequest& request, const JobHooks& hooks = {});

// The JSON `hexcal demo --json` prints.
nlohmann::json ToJson(const DemoResult& result);
// The closing lines `hexcal demo` prints.
std::string FormatDemoSummary(const DemoResult& result);

}  // namespace hexcal::workflow

// The request of the section 7 study (`hexcal simulate`; docs/calibration.md)
// and its options: the pose sets, the random set's size and box, the runs,
// seed, perturbation and threads of the simulation (core/simulation.h, taken
// whole), the weighting and the sweep — each described once in
// SimulateOptions() (core/option_spec.h). That table makes the `hexcal
// simulate` flags and the table in docs/cli.md, and Check() checks a request
// against it. The noise is NoiseModelOptions() (core/noise_model.h).
//
//   SimulateRequest request;  // random and boundary, 18 poses, 100 runs
//   Status s = ApplyOptionEntries(SimulateOptions(), {{"runs", "20"}, {"sweep", "8:41"}}, &request, "simulate");
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/option_spec.h"
#include "core/simulation.h"
#include "core/status.h"

namespace hexcal::workflow {

struct SimulateRequest {
  std::string robot;                     // robot file or preset name
  std::string sets = "random,boundary";  // comma-separated: random, boundary or pose CSV files
  int poses = 18;                        // poses of the random set
  bool poses_given = false;              // `poses` also trims the boundary set
  bool weighted = false;                 // calibrate with residuals weighted by the study's noise model
  std::string random_box;                // "x:-5:5,y:-5:5,..." for the random sets
  std::string sweep;                     // "MIN:MAX" poses for Fig. 15; empty: none
  std::string csv;                       // table to write; may be empty
  std::string plots;                     // folder for fig14/fig15 SVG and PNG; may be empty
  bool force = false;                    // replace an existing `csv` table or `plots` figures
  SimulationOptions study;               // runs, seed, perturbation, noise, threads
  std::vector<std::pair<std::string, std::string>> noise_entries;  // over study.noise (NoiseModelOptions)

  // The ranges of SimulateOptions(), then the simulation's own check; an
  // error names the option by its key (Status::option()).
  Status Check() const;
};

// The robot, the outputs (--csv, --plots, --force) and --json are not in it:
// they say where and how to run, not what the study is.
const OptionTable<SimulateRequest>& SimulateOptions();

}  // namespace hexcal::workflow

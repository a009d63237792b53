// Everything that decides a plan besides the robot and the noise model: the
// IOOPS options (core/ioops.h), how the candidate pool and the initial set
// are made, and the D-optimality certificate — each described once in
// PlanSetupOptions() (core/option_spec.h). That table makes the `hexcal plan`
// flags, the `planner:` section of a plan settings file, the GUI's Plan form
// and the table in docs/cli.md.
//
//   PlanSetup setup;  // the defaults
//   Status s = ApplyOptionEntries(PlanSetupOptions(), {{"tabu", "4"}, {"secondary", "O4"}}, &setup, "flags");
#pragma once

#include <string>
#include <vector>

#include "core/ioops.h"
#include "core/option_spec.h"

namespace hexcal::workflow {

// The defaults are the plan that calibrates best (docs/planner.md, "Defaults"):
// the S criterion, random and boundary candidates pooled, Tabu 4, and a
// continuous polish of the finite plan.
PlannerOptions DefaultPlannerOptions();

struct PlanSetup {
  PlannerOptions planner = DefaultPlannerOptions();
  std::vector<std::string> candidate_kinds = {"random", "boundary"};  // pooled generated sets
  int candidate_count = 0;        // poses per random/uniform set; 0: 10000 (continuous 2000)
  std::string init = "random";    // random | uniform | boundary | a pose CSV file
  bool certificate = true;        // the D-optimal design bound (finite candidate sets)
  double certificate_seconds = 60;  // its time limit, seconds
  // Continuous IOOPS iterations from the finite plan (its poses moved off the
  // candidate grid by SLSQP under every constraint); 0: none. With `continuous`
  // the finite plan is the start and the planner's own budget applies instead.
  int polish = 20;

  // The checks no single option can make (IsValid of PlannerOptions and the
  // criterion switch without a secondary); names the options to change.
  Status Check() const;
};

const OptionTable<PlanSetup>& PlanSetupOptions();

}  // namespace hexcal::workflow

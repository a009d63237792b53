#include "workflow/simulate_options.h"

#include <string>

#include "core/robot.h"

namespace hexcal::workflow {
namespace {

using Spec = OptionSpec<SimulateRequest>;

// An option whose range is the simulation's own rule (core/simulation.h), taken whole.
Spec Study(const std::string& key) {
  return NestedOption<SimulateRequest>(*FindOption(SimulationOptionSpecs(), key),
                                       [](SimulateRequest& r) -> SimulationOptions& { return r.study; });
}

}  // namespace

const OptionTable<SimulateRequest>& SimulateOptions() {
  static const OptionTable<SimulateRequest> table = [] {
    using Request = SimulateRequest;
    OptionTable<Request> t;
    t.push_back(TextOption<Request>("sets", "Pose sets", "comma-separated: random, boundary or pose CSV files",
                                    [](Request& r) -> std::string& { return r.sets; }));
    // Each leg's 7 parameters need 7 poses.
    t.push_back(NumberOption<Request>("poses", "Random poses", OptionType::kInteger, "poses", kParamsPerLeg, 100000,
                                      "poses of the random set (and, when given, of the boundary set: its first)",
                                      [](Request& r) -> int& { return r.poses; }));
    t.push_back(Study("runs"));
    t.push_back(Study("seed"));
    t.push_back(Study("perturb"));
    t.push_back(TextOption<Request>(
        "random_box", "Random box",
        "draw random sets in this box, e.g. x:-5:5,y:-5:5,z:50:57,q1:-20:20,q2:-20:20,q3:-20:20 (intersected "
        "with the robot's pose box; the robot's constraints still apply)",
        [](Request& r) -> std::string& { return r.random_box; }));
    t.push_back(
        NumberOption<Request>("weighted", "Weighted", OptionType::kFlag, "", 0, 1,
                              "calibrate with each residual divided by its standard deviation under the noise model",
                              [](Request& r) -> bool& { return r.weighted; }));
    t.push_back(Study("threads"));
    t.push_back(TextOption<Request>("sweep", "Sweep", "also the error against the number of poses, MIN:MAX (Fig. 15)",
                                    [](Request& r) -> std::string& { return r.sweep; }));
    return t;
  }();
  return table;
}

Status SimulateRequest::Check() const {
  if (Status s = CheckOptionRanges(SimulateOptions(), *this); !s.ok()) return s;
  return study.Check();
}

}  // namespace hexcal::workflow

#include "app/commands/help_examples.h"

#include <map>

namespace hexcal::cli {

// One table, so that a new command without an example is caught by
// app/help_examples_test.cc rather than by a user reading a bare --help. The
// examples chain as in the README's "Using it": `demo --out example` makes
// the session, images and camera the later ones use.
const std::map<std::string, std::string>& HelpExamples() {
  static const std::map<std::string, std::string> examples = {
      {"robot", "hexcal robot show inria-left-hand"},
      {"robot check", "hexcal robot check my-robot.yaml"},
      {"robot show", "hexcal robot show inria-left-hand"},
      {"ik", "hexcal ik --robot inria-left-hand --poses plan.csv --out legs.csv"},
      {"fk", "hexcal fk --robot inria-left-hand --legs 0,0,0,3.5,3.5,3.5 --all"},
      {"candidates", "hexcal candidates --robot inria-left-hand --kind boundary --out boundary.csv"},
      {"indices", "hexcal indices --robot inria-left-hand --poses boundary.csv"},
      {"demo", "hexcal demo --out example   # then: hexcal session status example"},
      {"plan", "hexcal plan --robot inria-left-hand --poses 18 --out plan.csv"},
      {"calibrate",
       "hexcal calibrate --session example\n"
       "  hexcal calibrate --robot inria-left-hand --measurements example/results/calibration_measurements.csv "
       "--out calibrated.yaml"},
      {"validate", "hexcal validate --robot calibrated.yaml --measurements held_out.csv"},
      {"simulate", "hexcal simulate --robot inria-left-hand --sets random,boundary,plan.csv --runs 100 --plots plots"},
      {"study",
       "hexcal study --session run64 --select 13   # run64: hexcal demo --poses 64 --holdout 0 "
       "--random-poses --out run64"},
      {"target", "hexcal target print --target aprilgrid-6x6 --out target.pdf"},
      {"target check", "hexcal target check --target aprilgrid-6x6"},
      {"target print", "hexcal target print --target aprilgrid-6x6 --out target.pdf"},
      {"detect", "hexcal detect --images example/images/view_0000.png --target aprilgrid-6x6"},
      {"render", "hexcal render --poses views.csv --out rendered   # views.csv: x,y,z,q1,q2,q3 of camera_from_target"},
      {"intrinsics", "hexcal intrinsics --target aprilgrid-6x6 --images example/images --out camera.yaml"},
      {"measure",
       "hexcal measure --camera camera.yaml --target aprilgrid-6x6 --images example/images --out camera_poses.csv"},
      {"session", "hexcal session status example"},
      {"session init",
       "hexcal session init run1 --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6"},
      {"session status", "hexcal session status example"},
      {"session check-noise", "hexcal session check-noise run1 --images still/   # k images of one pose"},
      {"session record",
       "hexcal session record run1 --image pose_0001.png --from capture.png --legs "
       "1.21,0.83,2.07,1.71,0.42,2.93"},
      {"report", "hexcal report --session example --out example-report.html"},
      {"acquire", "hexcal acquire --session run1 --controller sim --camera sim --holdout-every 4"},
      {"verify", "hexcal verify --session run1 --controller sim --camera sim --poses check.csv"},
      {"sim-camera", "hexcal sim-camera --session run1 --machine-robot /tmp/machine/robot.yaml"},
      {"export", "hexcal export --robot example/results/calibrated.yaml --format linuxcnc-hal --out calibrated.hal"},
      {"camera", "hexcal camera show camera.yaml"},
      {"camera show", "hexcal camera show camera.yaml"},
      {"camera convert", "hexcal camera convert camera.yaml --to ros --out camera_info.yaml"},
  };
  return examples;
}

std::string CommandPath(const CLI::App& command) {
  std::string path = command.get_name();
  for (const CLI::App* parent = command.get_parent(); parent != nullptr && parent->get_parent() != nullptr;
       parent = parent->get_parent()) {
    path = parent->get_name() + " " + path;
  }
  return path;
}

void AddHelpExamples(CLI::App& app) {
  if (app.get_parent() == nullptr) app.footer("Example:\n  hexcal demo --out example   # then README.md, \"Using it\"");
  for (CLI::App* sub : app.get_subcommands({})) {
    const auto example = HelpExamples().find(CommandPath(*sub));
    if (example != HelpExamples().end()) sub->footer("Example:\n  " + example->second);
    AddHelpExamples(*sub);
  }
}

}  // namespace hexcal::cli

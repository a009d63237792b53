#include "workflow/controller.h"

#include <chrono>
#include <cmath>
#include <thread>

#include "core/constraints.h"
#include "core/csv.h"
#include "workflow/linuxcnc_controller.h"
#include "workflow/sim_world.h"

namespace hexcal::workflow {
namespace {

Status BadUrl(const std::string& url, const std::string& problem) {
  return Status::Error("controller '" + url + "': " + problem + "; accepted forms: " + kControllerForms);
}

// The sim machine moves at once; settling is waited for as asked, so that a
// run's timing is that of the real machine's settle time.
class SimController final : public Controller {
 public:
  explicit SimController(std::shared_ptr<SimWorld> world) : world_(std::move(world)) {}

  Status MoveTo(const Vector6d& pose) override { return world_->Command(pose); }
  Status WaitSettled(double settle_seconds) override {
    if (settle_seconds > 0) std::this_thread::sleep_for(std::chrono::duration<double>(settle_seconds));
    return Status::Ok();
  }
  StatusOr<LegReadings> ReadLegs() override { return world_->ReadLegs(); }
  // The sim camera renders the pose the sim world holds: no latency to wait for.
  double DefaultSettleSeconds() const override { return 0; }
  std::string Describe() const override {
    return "sim controller (" + world_->scene().nominal.name + ", hidden true robot of seed " +
           std::to_string(world_->scene().seed) + ")";
  }

 private:
  std::shared_ptr<SimWorld> world_;
};

}  // namespace

StatusOr<std::unique_ptr<Controller>> OpenController(const std::string& url, const ControllerOptions& options) {
  if (url == "sim") {
    if (!options.sim) return Status::Error("controller 'sim' needs the session's sim world (OpenAcquisitionRig)");
    return std::unique_ptr<Controller>(std::make_unique<SimController>(options.sim));
  }
  if (url.rfind("linuxcnc://", 0) == 0) {
    StatusOr<LinuxCncAddress> address = ParseLinuxCncUrl(url);
    if (!address.ok()) return address.status();
    if (!options.robot) return Status::Error("controller '" + url + "' needs the session's robot (OpenAcquisitionRig)");
    return OpenLinuxCncController(*address, *options.robot);
  }
  return BadUrl(url, url.empty() ? "empty URL" : "unknown kind");
}

Status CheckPoseInWorkspace(const Robot& robot, const Vector6d& pose) {
  const ConstraintReport report = EvaluateConstraints(robot, robot.PoseFromVector(pose));
  if (report.feasible) return Status::Ok();
  return Status::Error("pose " + PoseText(pose) + " is out of the robot's workspace: " + report.worst_label + " by " +
                       FormatNumber(std::round(-report.worst_margin * 1e4) / 1e4));
}

Vector6d WorkspaceCentre(const Robot& robot) {
  Vector6d centre = Vector6d::Zero();
  if (const std::optional<PoseBox> box = robot.limits.SamplingBox(); box && box->IsComplete())
    for (int k = 0; k < 6; ++k) centre[k] = box->bounds[k]->Centre();
  return centre;
}

std::string PoseText(const Vector6d& pose) {
  std::string text = "(";
  for (int k = 0; k < 6; ++k) text += FormatNumber(pose[k]) + (k < 5 ? ", " : ")");
  return text;
}

}  // namespace hexcal::workflow

#include "workflow/controller.h"

#include <chrono>
#include <thread>

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
  if (url.rfind("linuxcnc://", 0) == 0)
    return BadUrl(url, "LinuxCNC through linuxcncrsh is not yet supported (docs/acquisition.md)");
  return BadUrl(url, url.empty() ? "empty URL" : "unknown kind");
}

}  // namespace hexcal::workflow

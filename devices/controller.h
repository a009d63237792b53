// Robot controllers for the Acquire step (docs/acquisition.md): one
// interface, opened from a URL, for the CLI (`hexcal acquire --controller URL`)
// and the GUI's Acquire step alike; OpenController (device_urls.h) opens one by URL.
//
//   sim                    the sim world (sim/sim_world.h): a hidden true
//                          robot that the nominal robot's IK drives
//   linuxcnc://HOST:PORT   a LinuxCNC hexapod (genhexkins) through linuxcncrsh
//                          (devices/linuxcnc_controller.h)
//
// Poses are plan.csv's: x, y, z in the robot's length unit, q1..q3 in degrees
// in the robot's Euler convention; readings are hexcal's L (robot unit).
//
//   StatusOr<std::unique_ptr<Controller>> robot = OpenController("sim", SimControllerOptions(world));
//   if (Status s = (*robot)->MoveTo(pose); !s.ok()) ...;
//   (*robot)->WaitSettled(0.5);
//   StatusOr<LegReadings> legs = (*robot)->ReadLegs();
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "core/inverse_kinematics.h"
#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::workflow {

class Controller {
 public:
  virtual ~Controller() = default;
  // Starts the move to `pose` (may return before it ends). An unreachable
  // pose is bad input naming the limit; a machine fault is a failure.
  virtual Status MoveTo(const Vector6d& pose) = 0;
  // Waits until the move has ended and then `settle_seconds` more (the
  // structure stops ringing before the camera exposes).
  virtual Status WaitSettled(double settle_seconds) = 0;
  // The six leg sensors now, L1..L6.
  virtual StatusOr<LegReadings> ReadLegs() = 0;
  // "sim controller (inria-left-hand, seed 1)": for logs.
  virtual std::string Describe() const = 0;
  // The settle time when the operator gives none, seconds: what this kind of
  // machine needs before a frame shows the pose it reports (see each one).
  virtual double DefaultSettleSeconds() const = 0;
  // False after a move that did not end where it should (a time-out, a stop
  // away from the target): more moves would fail the same way or worse, so
  // a run stops and the operator looks at the machine.
  virtual bool Usable() const { return true; }

  // A flag the caller raises to stop (Ctrl-C, the GUI's Cancel): WaitSettled
  // then stops the machine's motion and returns Cancelled rather than
  // waiting for the move or the settle time to end. Null: none.
  void SetCancelFlag(const std::atomic<bool>* cancel) { cancel_ = cancel; }

 protected:
  bool CancelRequested() const { return cancel_ != nullptr && cancel_->load(); }

 private:
  const std::atomic<bool>* cancel_ = nullptr;
};

struct ControllerOptions {
  // Opens the `sim` controller, which moves the sim world: set by
  // SimControllerOptions (sim/sim_world.h) for the world OpenAcquisitionRig
  // (workflow/acquire_step.h) makes, with the `sim` camera looking at it. The
  // devices know no world: the sim one sits above them (docs/architecture.md).
  std::function<std::unique_ptr<Controller>()> sim;
  // The session's nominal robot, which a `linuxcnc://` controller converts
  // poses and joints with (OpenAcquisitionRig loads it).
  std::shared_ptr<const Robot> robot;
};

// The accepted URL forms, for messages and --help.
constexpr const char* kControllerForms = "sim, linuxcnc://HOST:PORT";

// Every controller refuses a pose the robot cannot take before moving: bad
// input naming the pose and the limit it breaks by how much.
Status CheckPoseInWorkspace(const Robot& robot, const Vector6d& pose);
// "(1, 2, 53, 0, 0, 5)": a pose in messages.
std::string PoseText(const Vector6d& pose);

}  // namespace hexcal::workflow

// The forward-kinematics error a correct robot model shows on a measured pose
// when only the measurement noise is at work (docs/calibration.md, "Verdict"):
// what `held-out error` and `closure` in the verdict are compared with.
//
// FK from the readings L recovers the pose with the readings' noise carried
// through the inverse of the IK Jacobian J = ∂L/∂[P, θ] (inverse_kinematics.h),
// and is compared with a measured pose carrying its own noise, so
//   Cov(pose_fk − pose_measured) = σ_L² (JᵀJ)⁻¹ + diag(σ_p² I₃, σ_q² I₃)
// with σ the standard deviations of the session's uniform half-widths
// (noise_model.h; the Euler-angle noise is taken as rotation noise about each
// axis, exact to first order near zero angles). The expected RMS of the 3D
// position error is √trace of the position block, of the rotation angle √trace
// of the rotation block. The parameters' own uncertainty is left out: a
// calibration that is as good as its measurements adds less than they do.
//
//   ExpectedPoseError e = ExpectedFkError(robot, poses, noise);
//   double ratio = validation.after.position_rms / e.position_rms;  // ≈ 1 for a good calibration
#pragma once

#include <vector>

#include "core/noise_model.h"
#include "core/pose.h"
#include "core/robot.h"

namespace hexcal::workflow {

struct ExpectedPoseError {
  double position_rms = 0;         // robot unit
  double orientation_rms_deg = 0;  // degrees
};

// At one pose. At a singular pose (J not invertible) only the measured pose's
// noise is counted.
ExpectedPoseError ExpectedFkError(const Robot& robot, const Pose& pose, const NoiseModel& noise);
// The RMS over poses of the per-pose expectations; zeros for no poses.
ExpectedPoseError ExpectedFkError(const Robot& robot, const std::vector<Pose>& poses, const NoiseModel& noise);

}  // namespace hexcal::workflow

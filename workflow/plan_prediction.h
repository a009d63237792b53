// What a plan buys: the parameter uncertainty and held-out pose error a
// calibration from its poses is expected to leave (docs/planner.md,
// "Predicted error").
//
// The calibration is linear least squares near the truth, so its covariance
// follows from the Jacobian rows r_ij of eq. 5 and the residual variances
// v_ij = Var(F_ij) of the noise model (core/noise_model.h), leg by leg:
//   unweighted (calibrate's default)  C_i = A⁻¹ (Σ_j v_ij r_ij r_ijᵀ) A⁻¹,  A = Σ_j r_ij r_ijᵀ
//   weighted (--weighted)             C_i = (Σ_j r_ij r_ijᵀ / v_ij)⁻¹
// σ_k = √C_kk for each of the 42 parameters; an estimate with Gaussian error
// is off by √(2/π) σ on average, the figure `hexcal simulate` reports as
// "mean". A parameter error δp moves the pose FK recovers from fixed readings
// by δx = -G⁻¹ (r_i δp_i)_i, G the 6x6 of ∂F_i/∂(x, y, z, q) (noise_model.h),
// so the pose error from the parameters has covariance
// G⁻¹ diag(r_i C_i r_iᵀ) G⁻ᵀ; the held-out error adds the measurement noise's
// own FK error (expected_error.h).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "core/noise_model.h"
#include "core/planning_model.h"
#include "core/robot.h"
#include "report/expected_error.h"

namespace hexcal::workflow {

struct PlanPrediction {
  std::vector<double> sigma;  // the 42 parameter standard deviations, leg by leg (a, b, l), robot unit
  double mean_sigma = 0, max_sigma = 0;
  double mean_error = 0;      // √(2/π) mean σ: the expected mean |P_est - P_true|
  // Over the validation poses: the FK error the parameters' uncertainty adds,
  // and with the measurement noise's own (what held-out images show).
  ExpectedPoseError from_parameters, heldout;
  bool valid = false;         // false when a leg's information is singular
};

// The prediction for calibrating from `poses` ([x, y, z, q1, q2, q3]) with
// `noise`, checked on `validation` poses.
PlanPrediction PredictPlanError(const Robot& robot, const std::vector<Vector6d>& poses, const NoiseModel& noise,
                                bool weighted, const std::vector<Vector6d>& validation);
// The same with each pose's own covariance (a tracker's:
// PlanningModel::PoseCovariance, robot unit² and degrees²) in place of the
// noise model's pose terms in v_ij; the readings' noise, and the measurement
// noise of the held-out figure, stay the noise model's.
PlanPrediction PredictPlanError(const PlanningModel& model, const std::vector<Vector6d>& poses,
                                const NoiseModel& noise, bool weighted, const std::vector<Vector6d>& validation);

// 200 feasible random poses of the robot's sampling box (else its pose box),
// from a fixed seed: where a calibrated robot will be used, for the held-out figure.
std::vector<Vector6d> ValidationPoses(const Robot& robot);

// Each key of NoiseModelOptions() with its value: {"position", "angle_deg", "leg"}.
nlohmann::json NoiseModelJson(const NoiseModel& noise);

// {"mean_sigma", "max_sigma", "mean_error", "heldout_position_rms",
//  "heldout_orientation_rms_deg", "parameter_position_rms", "parameter_orientation_rms_deg",
//  "weighted", "noise": {...}}
nlohmann::json ToJson(const PlanPrediction& prediction, const NoiseModel& noise, bool weighted);

}  // namespace hexcal::workflow

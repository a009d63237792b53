// The platform's pose from reflector points a laser tracker measured
// (issue 38, docs/calibration.md, "Point measurements"): the rigid motion that
// takes the reflectors' known positions (in a frame fixed to the platform) to
// where the tracker saw them, weighted by each point's σ, with its
// covariance. The tracker's frame then plays the camera's part and the
// reflectors' frame the target's: the registration (core/registration.h)
// estimates both, so the reflectors need not be known in the platform frame
// itself, only in one frame rigidly attached to it.
//
// Model: m_k = R p_k + t + e_k, e_k ~ N(0, σ_k² I). The estimate minimises
// Σ |R p_k + t − m_k|² / σ_k² (weighted Kabsch: the weighted centroids, then
// the SVD of the weighted cross-covariance, det fixed to +1); its covariance
// is (JᵀWJ)⁻¹ for the increment [δt, θ] with R ← exp([θ]×) R, mapped to the
// pose vector VectorFromPose(·, kXYZ) (robot unit, degrees) by central
// differences, as the board pose's (vision/board_pose.h).
//
//   StatusOr<PointFit> fit = FitPointPose(reflectors, seen);
//   fit->pose;        // tracker_from_reflectors
//   fit->covariance;  // of VectorFromPose(fit->pose, kXYZ)
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/pose.h"
#include "core/status.h"

namespace hexcal {

// One reflector: its name, where it is (reflector frame, or as measured), and
// the σ of each coordinate (0 in a reflector list).
struct NamedPoint {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double sigma = 0;
};

struct PointFit {
  Pose pose;           // tracker_from_reflectors
  Matrix6d covariance = Matrix6d::Zero();  // of VectorFromPose(pose, kXYZ): unit², degrees²
  double rms = 0;      // of the residual distances, unit
  std::vector<double> residuals;  // |R p_k + t − m_k| of each measured point, unit, in its order
};

// A point this many σ from where the others put it is named an outlier.
constexpr double kPointOutlierSigmas = 10;

// Fits the measured points to the reflectors of the same names. Bad input
// naming the point: fewer than 3 points, a name measured twice or not among
// the reflectors, a σ not positive, collinear reflectors (the rotation about
// their line is free); with 4 or more points, one that lies more than
// kPointOutlierSigmas σ from where the others put it (the worst, with its
// distance), and a distance ratio between the measured and the known points
// far from 1 (another length unit).
StatusOr<PointFit> FitPointPose(const std::vector<NamedPoint>& reflectors, const std::vector<NamedPoint>& measured);

// The covariance of VectorFromPose(pose, convention) (unit², degrees²) that
// FitPointPose states for the reflectors `known` (their own frame) seen,
// without noise, at `pose` · known, each coordinate of point k with σ
// sigmas[k]: (JᵀWJ)⁻¹ at a pose not yet measured, for the planner's per-pose
// noise (core/tracker_model.h). 3 or more points, not collinear (assert).
Matrix6d PointPoseCovariance(const Pose& pose, const std::vector<Eigen::Vector3d>& known,
                             const std::vector<double>& sigmas, EulerConvention convention);

// The σ of a pose fitted to these reflectors when each coordinate of each is
// measured with σ `sigma` (the covariance FitPointPose states for noiseless
// points at the reflectors' own frame): what a tracker's noise means for the
// pose, before any pose is measured — the session's noise model for planning.
// {position σ (mean over x, y, z; unit), angle σ (mean over q1..q3; degrees)}.
StatusOr<std::pair<double, double>> PoseSigmaOfReflectors(const std::vector<NamedPoint>& reflectors, double sigma);

}  // namespace hexcal

// What a calibration from points (core/point_calibration.h) adds to
// results/report.json: the fit's residuals, the reflectors it estimated with
// their σ, the scale of their shape against the reflector file's, the
// identifiability figures, and the two-stage calibration it started from, for
// the comparison (docs/calibration.md, "Calibration from points").
//
//   if (report.from_points) for (const ReflectorSummary& r : report.from_points->reflectors) Show(r);
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "session/json_fields.h"
#include "session/pixel_fit_summary.h"

namespace hexcal::workflow {

// One reflector, in the reflector file's frame (or, estimated from the poses,
// the frame of that estimate): as given, as fitted, and the fit's σ.
struct ReflectorSummary {
  std::string name;
  Eigen::Vector3d given = Eigen::Vector3d::Zero(), estimate = Eigen::Vector3d::Zero();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();  // of x, y, z; 0 when held
};

struct PointFitSummary {
  int poses = 0, points = 0, leg_rows = 0;
  double point_rms = 0;         // RMS of |predicted − measured| per point, robot unit
  double leg_residual_rms = 0;  // robot unit
  double variance_factor = 0;
  int iterations = 0;
  bool reflectors_estimated = false;
  bool reflectors_from_file = true;  // false: the given ones were estimated from the poses
  std::vector<ReflectorSummary> reflectors;
  // The fitted shape's size over the given one's (RMS distance from the
  // centroid), with its σ: 1 when the reflector file and the tracker agree.
  double reflector_scale = 1, reflector_scale_sigma = 0;
  double largest_reflector_correlation = 0;  // |correlation| of a reflector coordinate with a parameter
  int unknowns = 0, rank = 0;                // of the reduced information (42 + 3K − 6 estimated)
  double eigenvalue_ratio = 0;               // its smallest / largest eigenvalue, unknowns scaled
  TwoStageComparison two_stage;
  double mean_parameter_sigma = 0;  // robot unit, of this fit
};

nlohmann::json ToJson(const PointFitSummary& summary);
// The lines `calibrate --session` prints for it (`unit`: the robot's length unit).
std::string FormatPointFitSummary(const PointFitSummary& summary, const std::string& unit);
// Reads what ToJson wrote; problems go to `fields`' status.
PointFitSummary PointFitSummaryFromJson(JsonFields fields);

}  // namespace hexcal::workflow

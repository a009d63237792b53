// The chart definitions: every figure hexcal draws, each a function from
// plain data to a ChartSpec. The GUI panels, the HTML report and
// `hexcal simulate --plots` all draw from these, so a figure that appears in
// two places is defined once (the leg readings of a plan, the calibration
// residuals).
//
//   ChartSpec fig14 = Fig14Chart(result, "mm");         // simulate --plots
//   ChartSpec legs = LegReadingsChart(robot, plan);      // report and plan panel
//   QChart* chart = NewQtChart(legs);                    // qt_chart.h, or
//   StatusOr<std::string> svg = ChartSvgElement(legs);   // chart_render.h
#pragma once

#include <string>
#include <vector>

#include "charts/chart_spec.h"
#include "core/ioops.h"
#include "core/measurements.h"
#include "core/robot.h"
#include "core/simulation.h"
#include "core/subset_study.h"

namespace hexcal::charts {

// --- The section 7 study (core/simulation.h) ---

// Fig. 14: bars of the mean ± std of |P_est - P_true| on a log axis: before
// calibration, then each pose set ("name (poses)").
ChartSpec Fig14Chart(const SimulationResult& result, const std::string& length_unit);
// Fig. 15: one line per set, the mean (or, with `std_dev`, the standard
// deviation) of |P_est - P_true| against the number of poses, log axis.
ChartSpec Fig15Chart(const SweepResult& sweep, const std::string& length_unit, bool std_dev);

// --- The section 8 study (core/subset_study.h) ---

// Figs. 18, 19: the histogram of a quantity over the random subsets, as the
// outline of `bins` equal bins over [min, max] of the values and `selected`
// (y: subsets per bin), with the selected subset's value as a dashed
// vertical line. Non-finite values are left out.
ChartSpec SubsetHistogramChart(const std::string& title, const std::string& x_label, const std::vector<double>& random,
                               double selected, int bins = 40);
// The study's figure of one metric: Fig. 18 for an index, Fig. 19 for a
// held-out error, titled with the subset size N = `select` (the legend
// counts the random subsets; a title short enough for a GUI chart).
// `hexcal study --plots`, the session's study/ folder, the HTML report and
// the GUI's study view all draw this one.
ChartSpec StudyMetricChart(SubsetMetric metric, const std::vector<double>& random, double selected, int select,
                           const std::string& length_unit);

// --- Planning ---

// Fig. 8: the reading of each leg at each pose of `plan` (x: pose 1..N, one
// series per leg), with the stroke limits as dashed lines. Report and GUI.
ChartSpec LegReadingsChart(const Robot& robot, const std::vector<Vector6d>& plan);
// Figs. 6, 10-12: O1..O4 of the plan after each planner iteration, log axis.
// The GUI starts it empty and appends each iteration live (qt_chart.h,
// AppendPoint to series 0..3); the point of iteration i for O(k+1) is
// {i, index k}.
ChartSpec ObservabilityChart(const std::vector<PlanIteration>& iterations);
// O1..O4 of `indices`, in the order of ObservabilityChart's series.
std::vector<double> IndexValues(const ObservabilityIndices& indices);

// --- Measurement, calibration, validation ---

// The reprojection RMS (px) of each image in camera_poses.csv order.
ChartSpec MeasurementRmsChart(const std::vector<double>& rms_px);
// The implicit residual IK(pose) - reading (paper eq. 4, as a length) of
// every leg at every calibration pose, with the nominal and the calibrated
// robot; signed, so over- and under-long legs both show. Report and GUI.
ChartSpec CalibrationResidualsChart(const Robot& nominal, const Robot& calibrated,
                                    const std::vector<Measurement>& rows);

struct ParameterChange {
  int leg = 0;        // 1..6
  std::string name;   // "a_x", "l", ...
  double change = 0;  // calibrated - nominal, robot unit (or none for angles)
  double sigma = 0;   // 1 sigma of the estimate; NaN or 0: unknown, no error bar
};
// Calibrated minus nominal of every parameter, ± 1 sigma: one group of bars
// per parameter name (a_x ... l), one bar per leg. Changes can be negative,
// and the axis holds them.
ChartSpec ParameterChangeChart(const std::vector<ParameterChange>& changes, const std::string& length_unit);

// The held-out validation errors (FK from the readings against the camera).
struct ValidationErrors {
  double position_before = 0;  // robot unit
  double position_after = 0;
  double orientation_before = 0;  // degrees
  double orientation_after = 0;
};
// RMS position and orientation error before and after calibration, grouped
// bars on a log axis (the errors shrink by orders of magnitude). Report.
ChartSpec ValidationSummaryChart(const ValidationErrors& rms, const std::string& length_unit);

struct ImageValidation {
  std::string image;  // a short label: the number in the image name
  ValidationErrors errors;
};
enum class ValidationQuantity { kPosition, kOrientation };
// One group of before/after bars per held-out image, or pose: `noun` names
// what a row of legs.csv is ("image", a points session's "pose"). GUI.
ChartSpec ValidationPerImageChart(const std::vector<ImageValidation>& images, ValidationQuantity quantity,
                                  const std::string& length_unit, const std::string& noun = "image");

}  // namespace hexcal::charts

#include "charts/figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/inverse_kinematics.h"

namespace hexcal::charts {
namespace {

// "label (unit)", or the label alone before the unit is known (an empty GUI chart).
std::string WithUnit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " (" + unit + ")";
}

std::string ParameterErrorLabel(const std::string& unit) { return WithUnit("|P_est - P_true|", unit); }

// The dashed stroke lines over poses 1..last: one per distinct limit, named
// after the legs that have it when the legs differ.
void AddStrokeLines(const Robot& robot, double last, ChartSpec* spec) {
  for (bool upper : {false, true}) {
    std::map<double, std::string> legs_at;  // limit -> "1,2,..."
    for (int i = 0; i < kNumLegs; ++i) {
      std::string& legs = legs_at[upper ? robot.legs[i].stroke_max : robot.legs[i].stroke_min];
      legs += (legs.empty() ? "" : ",") + std::to_string(i + 1);
    }
    for (const auto& [limit, legs] : legs_at) {
      std::string name = upper ? "stroke max" : "stroke min";
      if (legs_at.size() > 1) name += " (legs " + legs + ")";
      spec->series.push_back(LineSeries(name, {{1, limit}, {last, limit}}, /*dashed=*/true));
    }
  }
}

}  // namespace

ChartSpec Fig14Chart(const SimulationResult& result, const std::string& length_unit) {
  ChartSpec spec;
  spec.title = "Fig. 14: parameter error before and after calibration (mean ± std)";
  spec.y = LogAxis(ParameterErrorLabel(length_unit));
  std::vector<double> means = {result.before.mean}, stds = {result.before.std};
  spec.x.categories = {"before"};
  for (const SetError& set : result.sets) {
    spec.x.categories.push_back(set.name + " (" + std::to_string(set.poses) + ")");
    means.push_back(set.mean);
    stds.push_back(set.std);
  }
  spec.series.push_back(BarSeries("mean ± std", means, stds));
  return spec;
}

ChartSpec Fig15Chart(const SweepResult& sweep, const std::string& length_unit, bool std_dev) {
  ChartSpec spec;
  spec.title = std::string("Fig. 15: ") + (std_dev ? "standard deviation" : "mean") +
               " of the parameter error against the number of poses";
  spec.x = LinearAxis("number of poses");
  spec.y = LogAxis(std::string(std_dev ? "std " : "mean ") + ParameterErrorLabel(length_unit));
  std::map<std::string, size_t> index;  // set name -> series, in order of first appearance
  for (const SweepPoint& point : sweep.points) {
    for (const SetError& set : point.sets) {
      auto [it, added] = index.emplace(set.name, spec.series.size());
      if (added) spec.series.push_back(LineSeries(set.name, {}));
      spec.series[it->second].points.push_back({static_cast<double>(point.poses), std_dev ? set.std : set.mean});
    }
  }
  return spec;
}

ChartSpec LegReadingsChart(const Robot& robot, const std::vector<Vector6d>& plan) {
  ChartSpec spec;
  spec.title = "Leg readings of the " + std::to_string(plan.size()) + " planned poses (Fig. 8)";
  spec.x = LinearAxis("pose");
  spec.y = LinearAxis(WithUnit("reading L", LengthUnitName(robot.length_unit)));
  // Points, not lines: consecutive poses are unrelated, and lines between
  // them would hide where the readings crowd.
  for (int i = 0; i < kNumLegs; ++i) spec.series.push_back(ScatterSeries("L" + std::to_string(i + 1), {}));
  for (size_t j = 0; j < plan.size(); ++j) {
    const LegReadings legs = InverseKinematics(robot, robot.PoseFromVector(plan[j]));
    for (int i = 0; i < kNumLegs; ++i) spec.series[i].points.push_back({static_cast<double>(j + 1), legs[i]});
  }
  // Planned poses crowd at the stroke ends (section 4): the limits show it.
  if (!plan.empty()) AddStrokeLines(robot, std::max<double>(2, plan.size()), &spec);
  return spec;
}

ChartSpec ObservabilityChart(const std::vector<PlanIteration>& iterations) {
  ChartSpec spec;
  spec.title = "Observability indices per iteration (figs 6, 10–12)";
  spec.x = LinearAxis("iteration");
  spec.y = LogAxis("index");
  for (int k = 0; k < 4; ++k) spec.series.push_back(LineSeries("O" + std::to_string(k + 1), {}));
  for (const PlanIteration& step : iterations) {
    const std::vector<double> values = IndexValues(step.indices);
    for (int k = 0; k < 4; ++k) spec.series[k].points.push_back({static_cast<double>(step.iteration), values[k]});
  }
  return spec;
}

std::vector<double> IndexValues(const ObservabilityIndices& indices) {
  return {indices.o1, indices.o2, indices.o3, indices.o4};
}

ChartSpec MeasurementRmsChart(const std::vector<double>& rms_px) {
  ChartSpec spec;
  spec.title = "Measurement quality";
  spec.x = LinearAxis("image (camera_poses.csv order)");
  spec.y = LinearAxis("reprojection RMS (px)");
  std::vector<ChartPoint> points;
  for (size_t r = 0; r < rms_px.size(); ++r) points.push_back({static_cast<double>(r + 1), rms_px[r]});
  spec.series.push_back(LineSeries("reprojection RMS", points));
  return spec;
}

ChartSpec CalibrationResidualsChart(const Robot& nominal, const Robot& calibrated,
                                    const std::vector<Measurement>& rows) {
  ChartSpec spec;
  spec.title = "Calibration residuals: IK(pose) - reading of every leg";
  spec.x = LinearAxis("calibration pose (legs 1–6 left to right)");
  spec.y = LinearAxis(WithUnit("residual", LengthUnitName(nominal.length_unit)));
  SeriesSpec before = ScatterSeries("nominal robot", {}), after = ScatterSeries("calibrated robot", {});
  for (size_t j = 0; j < rows.size(); ++j) {
    const Measurement& m = rows[j];
    const LegReadings r0 = InverseKinematics(nominal, nominal.PoseFromVector(m.pose)) - m.legs;
    const LegReadings r1 = InverseKinematics(calibrated, calibrated.PoseFromVector(m.pose)) - m.legs;
    for (int i = 0; i < kNumLegs; ++i) {
      const double x = static_cast<double>(j + 1) + (i - 2.5) / kNumLegs;  // the six legs around the pose number
      before.points.push_back({x, r0[i]});
      after.points.push_back({x, r1[i]});
    }
  }
  spec.series = {before, after};
  return spec;
}

ChartSpec ParameterChangeChart(const std::vector<ParameterChange>& changes, const std::string& length_unit) {
  ChartSpec spec;
  spec.title = "Calibrated minus nominal, with 1 sigma";
  spec.x = CategoryAxis("parameter", {});
  spec.y = LinearAxis(WithUnit("change", length_unit));
  spec.width = 900;
  // 42 bars in a row leave no room for their labels: group them by name.
  std::map<std::string, size_t> category;  // name -> index, in order of appearance
  std::map<int, size_t> series;            // leg -> series
  for (const ParameterChange& p : changes) {
    if (category.emplace(p.name, spec.x.categories.size()).second) spec.x.categories.push_back(p.name);
    if (series.emplace(p.leg, spec.series.size()).second)
      spec.series.push_back(BarSeries("leg " + std::to_string(p.leg), {}, {}));
  }
  for (SeriesSpec& s : spec.series) {  // a parameter a leg does not have: no bar
    s.values.assign(spec.x.categories.size(), std::numeric_limits<double>::quiet_NaN());
    s.errors.assign(spec.x.categories.size(), 0);
  }
  for (const ParameterChange& p : changes) {
    SeriesSpec& s = spec.series[series[p.leg]];
    s.values[category[p.name]] = p.change;
    s.errors[category[p.name]] = p.sigma;
  }
  return spec;
}

ChartSpec ValidationSummaryChart(const ValidationErrors& rms, const std::string& length_unit) {
  ChartSpec spec;
  spec.title = "Held-out validation (forward kinematics against the camera)";
  spec.x = CategoryAxis("", {WithUnit("position", length_unit), "orientation (deg)"});
  spec.y = LogAxis("RMS error");
  spec.series.push_back(BarSeries("nominal robot (before)", {rms.position_before, rms.orientation_before}));
  spec.series.push_back(BarSeries("calibrated robot (after)", {rms.position_after, rms.orientation_after}));
  return spec;
}

ChartSpec ValidationPerImageChart(const std::vector<ImageValidation>& images, ValidationQuantity quantity,
                                  const std::string& length_unit, const std::string& noun) {
  const bool position = quantity == ValidationQuantity::kPosition;
  ChartSpec spec;
  spec.title = std::string(position ? "Held-out position error per " : "Held-out orientation error per ") + noun;
  spec.x = CategoryAxis(noun + " number", {});
  spec.y = LinearAxis(position ? WithUnit("position error", length_unit) : "orientation error (deg)");
  std::vector<double> before, after;
  for (const ImageValidation& image : images) {
    spec.x.categories.push_back(image.image);
    before.push_back(position ? image.errors.position_before : image.errors.orientation_before);
    after.push_back(position ? image.errors.position_after : image.errors.orientation_after);
  }
  spec.series.push_back(BarSeries("before", before));
  spec.series.push_back(BarSeries("after", after));
  return spec;
}

ChartSpec SubsetHistogramChart(const std::string& title, const std::string& x_label, const std::vector<double>& random,
                               double selected, int bins) {
  std::vector<double> values;
  for (double v : random)
    if (std::isfinite(v)) values.push_back(v);
  double lo = std::isfinite(selected) ? selected : 0, hi = lo;
  for (double v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (hi <= lo) hi = lo + 1;  // every value equal: one unit wide, the values in the first bin
  bins = std::max(bins, 1);
  const double width = (hi - lo) / bins;
  std::vector<int> counts(bins, 0);
  for (double v : values) ++counts[std::min(bins - 1, static_cast<int>((v - lo) / width))];
  std::vector<ChartPoint> outline = {{lo, 0}};
  int tallest = 0;
  for (int k = 0; k < bins; ++k) {
    outline.push_back({lo + k * width, static_cast<double>(counts[k])});
    outline.push_back({lo + (k + 1) * width, static_cast<double>(counts[k])});
    tallest = std::max(tallest, counts[k]);
  }
  outline.push_back({hi, 0});
  ChartSpec spec;
  spec.title = title;
  spec.x = LinearAxis(x_label);
  spec.y = LinearAxis("random subsets");
  spec.series.push_back(LineSeries(std::to_string(values.size()) + " random subsets", outline));
  if (std::isfinite(selected)) {
    spec.series.push_back(
        LineSeries("selected subset", {{selected, 0}, {selected, static_cast<double>(std::max(tallest, 1))}}, true));
  }
  return spec;
}

ChartSpec StudyMetricChart(SubsetMetric metric, const std::vector<double>& random, double selected, int select,
                           const std::string& length_unit) {
  const std::string label = SubsetMetricLabel(metric, length_unit);
  const std::string title =
      std::string(HigherIsBetter(metric) ? "Fig. 18: " : "Fig. 19: ") + label + ", N = " + std::to_string(select);
  return SubsetHistogramChart(title, label, random, selected);
}

}  // namespace hexcal::charts

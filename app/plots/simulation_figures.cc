#include "app/plots/simulation_figures.h"

#include <filesystem>
#include <map>

#include "app/plots/png_render.h"
#include "app/plots/svg_chart.h"
#include "core/atomic_file.h"

namespace hexcal::plots {
namespace {

Status WriteBoth(const std::string& directory, const std::string& stem, const std::string& svg,
                 const ChartOptions& options, std::vector<std::string>* written) {
  const std::string svg_path = (std::filesystem::path(directory) / (stem + ".svg")).string();
  const std::string png_path = (std::filesystem::path(directory) / (stem + ".png")).string();
  if (Status s = WriteFileAtomically(svg_path, svg); !s.ok()) return s;
  written->push_back(svg_path);
  if (Status s = WriteSvgAsPng(svg, png_path, options.width, options.height); !s.ok()) return s;
  written->push_back(png_path);
  return Status::Ok();
}

ChartOptions Fig14Options(const std::string& unit) {
  ChartOptions options;
  options.title = "Fig. 14: parameter error before and after calibration (mean ± std)";
  options.y_label = "|P_est - P_true| (" + unit + ")";
  options.log_y = true;
  return options;
}

ChartOptions Fig15Options(const std::string& unit, bool std_dev) {
  ChartOptions options;
  options.title = std::string("Fig. 15: ") + (std_dev ? "standard deviation" : "mean") +
                  " of the parameter error against the number of poses";
  options.x_label = "number of poses";
  options.y_label = std::string(std_dev ? "std" : "mean") + " |P_est - P_true| (" + unit + ")";
  options.log_y = true;
  return options;
}

}  // namespace

std::string Fig14Svg(const SimulationResult& result, const std::string& length_unit) {
  std::vector<Bar> bars = {{"before", result.before.mean, result.before.std}};
  for (const SetError& set : result.sets) {
    bars.push_back({set.name + " (" + std::to_string(set.poses) + ")", set.mean, set.std});
  }
  return BarChartSvg(Fig14Options(length_unit), bars);
}

std::string Fig15Svg(const SweepResult& sweep, const std::string& length_unit, bool std_dev) {
  std::vector<LineSeries> series;
  std::map<std::string, size_t> index;  // set name -> series
  for (const SweepPoint& point : sweep.points) {
    for (const SetError& set : point.sets) {
      auto [it, added] = index.emplace(set.name, series.size());
      if (added) series.push_back({set.name, {}, {}});
      series[it->second].x.push_back(point.poses);
      series[it->second].y.push_back(std_dev ? set.std : set.mean);
    }
  }
  return LineChartSvg(Fig15Options(length_unit, std_dev), series);
}

Status WriteSimulationFigures(const std::string& directory, const SimulationResult& result, const SweepResult* sweep,
                              const std::string& length_unit, std::vector<std::string>* written) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) return Status::Error(directory + ": cannot create the plots folder: " + error.message());
  if (Status s = WriteBoth(directory, "fig14", Fig14Svg(result, length_unit), Fig14Options(length_unit), written);
      !s.ok()) {
    return s;
  }
  if (sweep == nullptr) return Status::Ok();
  for (bool std_dev : {false, true}) {
    if (Status s = WriteBoth(directory, std_dev ? "fig15_std" : "fig15_mean", Fig15Svg(*sweep, length_unit, std_dev),
                             Fig15Options(length_unit, std_dev), written);
        !s.ok()) {
      return s;
    }
  }
  return Status::Ok();
}

}  // namespace hexcal::plots

// The figures of the section 7 study (core/simulation.h) as SVG charts and
// PNG files: Fig. 14, the parameter error of each pose set next to the error
// before calibration, and Fig. 15, the error against the number of poses.
//
//   std::vector<std::string> written;
//   Status s = WriteSimulationFigures("plots", result, &sweep, "cm", &written);
#pragma once

#include <string>
#include <vector>

#include "core/simulation.h"

namespace hexcal::plots {

// Bars of mean ± std of |P_est - P_true| (log axis): before calibration, then each set.
std::string Fig14Svg(const SimulationResult& result, const std::string& length_unit);
// One line per set: the mean (or, with `std_dev`, the standard deviation) of the error against n.
std::string Fig15Svg(const SweepResult& sweep, const std::string& length_unit, bool std_dev);

// Writes fig14.svg/.png and, with a sweep, fig15_mean.svg/.png and fig15_std.svg/.png
// into `directory` (created if missing); appends each path written to `written`.
Status WriteSimulationFigures(const std::string& directory, const SimulationResult& result, const SweepResult* sweep,
                              const std::string& length_unit, std::vector<std::string>* written);

}  // namespace hexcal::plots

// The panels' chart views: each shows a figure of charts/figures.h, drawn by
// charts/qt_chart.h, the same code that draws the report's and the CLI's
// charts. Live plots append to the view's chart with charts::AppendPoint.
//
//   charts::ChartSpec spec = charts::ObservabilityChart({});
//   QtCharts::QChartView* view = MakeChartView(spec);
//   charts::AppendPoint(view->chart(), &spec, 0, {iteration, o1});
#pragma once

#include "charts/chart_spec.h"

namespace QtCharts {
class QChartView;
}

namespace hexcal::ui {

QtCharts::QChartView* MakeChartView(const charts::ChartSpec& spec);
// Replaces what the view shows.
void ShowChart(QtCharts::QChartView* view, const charts::ChartSpec& spec);

}  // namespace hexcal::ui

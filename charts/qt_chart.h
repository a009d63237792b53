// A ChartSpec drawn with Qt Charts: the one code path behind the GUI's chart
// views and the offscreen SVG/PNG files (chart_render.h). The axes are
// ComputeRanges(spec), so what the tests check of a spec is what is drawn.
// Qt Charts has no error bars: each is a small polyline (bar, caps) in the
// bars' colour scheme, left out of the legend.
//
//   auto* view = new QtCharts::QChartView(NewQtChart(ObservabilityChart({})));
//   ChartSpec spec = ObservabilityChart({});
//   FillQtChart(view->chart(), spec);                      // replace all
//   AppendPoint(view->chart(), &spec, 0, {iteration, o1});  // live: one point
//
// Like every QGraphicsItem, a QChart belongs to the GUI thread.
#pragma once

#include "charts/chart_spec.h"

namespace QtCharts {
class QChart;
}

namespace hexcal::charts {

// A new chart of `spec` (spec.IsValid() must hold). The caller owns it, or
// hands it to a QChartView or a QGraphicsScene.
QtCharts::QChart* NewQtChart(const ChartSpec& spec);

// Replaces what `chart` draws (title, series, axes) with `spec`.
void FillQtChart(QtCharts::QChart* chart, const ChartSpec& spec);

// Live plots: appends `point` to line or scatter series `index` of `spec`
// and of `chart`, which shows `spec` (FillQtChart), and widens the axes to
// ComputeRanges(*spec). A point a log axis cannot hold is kept in `spec` but
// not drawn. Cheaper than FillQtChart: the other series stay as they are.
void AppendPoint(QtCharts::QChart* chart, ChartSpec* spec, int index, ChartPoint point);

}  // namespace hexcal::charts

#include "ui/charts.h"

#include <QChartView>

#include "charts/qt_chart.h"

namespace hexcal::ui {

QtCharts::QChartView* MakeChartView(const charts::ChartSpec& spec) {
  auto* view = new QtCharts::QChartView(charts::NewQtChart(spec));
  view->setRenderHint(QPainter::Antialiasing);
  view->setMinimumHeight(200);
  return view;
}

void ShowChart(QtCharts::QChartView* view, const charts::ChartSpec& spec) { charts::FillQtChart(view->chart(), spec); }

}  // namespace hexcal::ui

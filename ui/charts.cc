#include "ui/charts.h"

#include <QAbstractAxis>
#include <QCategoryAxis>
#include <QChartView>
#include <QLegend>
#include <vector>

#include "charts/qt_chart.h"

namespace hexcal::ui {
namespace {

constexpr int kMaxVerticalTicks = 6;

// Every other tick label of a linear vertical axis with more than six, the
// one at 0 kept: Qt gives each label an axis height / count band and elides
// ("...") a label taller than its band, which a chart sharing 720 px is.
void ThinVerticalTicks(QtCharts::QChart* chart) {
  for (QtCharts::QAbstractAxis* axis : chart->axes(Qt::Vertical)) {
    auto* ticks = qobject_cast<QtCharts::QCategoryAxis*>(axis);
    if (ticks == nullptr || ticks->count() <= kMaxVerticalTicks) continue;
    const QStringList labels = ticks->categoriesLabels();
    const int zero = std::max(0, static_cast<int>(labels.indexOf("0")));
    std::vector<std::pair<QString, double>> kept;
    for (int k = 0; k < labels.size(); ++k)
      if ((k - zero) % 2 == 0) kept.push_back({labels[k], ticks->endValue(labels[k])});
    for (const QString& label : labels) ticks->remove(label);
    for (const auto& [label, value] : kept) ticks->append(label, value);
  }
}

// Fonts a step smaller than the report's and thin margins: at 1280x720 a
// chart shares its panel with a table, and Qt Charts elides a vertical axis's
// labels once the plot is shorter than about one label per sixth of its
// height (seen as "..." ticks on the residual chart, docs/gui.md).
void Compact(QtCharts::QChart* chart) {
  QFont labels = chart->font();
  labels.setPointSizeF(labels.pointSizeF() * 0.85);
  QFont title = chart->titleFont();
  title.setPointSizeF(labels.pointSizeF() * 1.1);
  chart->setTitleFont(title);
  chart->setMargins(QMargins(4, 2, 4, 2));
  chart->legend()->setFont(labels);
  for (QtCharts::QAbstractAxis* axis : chart->axes()) {
    axis->setLabelsFont(labels);
    axis->setTitleFont(labels);
  }
  ThinVerticalTicks(chart);
}

}  // namespace

QtCharts::QChartView* MakeChartView(const charts::ChartSpec& spec) {
  auto* view = new QtCharts::QChartView(charts::NewQtChart(spec));
  view->setRenderHint(QPainter::Antialiasing);
  view->setMinimumHeight(160);  // room for the axes at 1024×600; layouts give more
  Compact(view->chart());
  return view;
}

void ShowChart(QtCharts::QChartView* view, const charts::ChartSpec& spec) {
  // A new chart, not the old one refilled: refilled while its view was hidden
  // (the Plan panel's indices during a run), the removed axes stayed drawn
  // over the new ones.
  QtCharts::QChart* old = view->chart();
  view->setChart(charts::NewQtChart(spec));
  delete old;  // setChart gives up the old one
  Compact(view->chart());
}

}  // namespace hexcal::ui

// Qt Charts helpers for the panels: line charts (indices per iteration, leg
// lengths per pose, residuals) and grouped bars (validation before/after).
#pragma once

#include <QPointF>
#include <QString>
#include <QStringList>
#include <vector>

namespace QtCharts {
class QChartView;
}

namespace hexcal::ui {

struct LineData {
  QString name;
  std::vector<QPointF> points;
  bool dashed = false;   // limits and references
  bool markers = false;  // scatter-like: points only
};

QtCharts::QChartView* MakeChartView(const QString& title, const QString& x_title, const QString& y_title);
// Replaces the chart's series. `log_y` needs positive values (others are dropped).
void SetLines(QtCharts::QChartView* view, const std::vector<LineData>& lines, bool log_y = false);
// Appends one point to series `index` (made if missing) and widens the axes: live plots.
void AppendPoint(QtCharts::QChartView* view, int index, const QString& name, QPointF point);
// Grouped bars: one set per entry of `sets`, one group per category.
void SetBars(QtCharts::QChartView* view, const QStringList& categories,
             const std::vector<std::pair<QString, std::vector<double>>>& sets);

}  // namespace hexcal::ui

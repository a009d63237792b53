#include "ui/charts.h"

#include <QBarCategoryAxis>
#include <QBarSeries>
#include <QBarSet>
#include <QChart>
#include <QChartView>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QScatterSeries>
#include <QValueAxis>
#include <algorithm>
#include <cmath>

using namespace QtCharts;

namespace hexcal::ui {
namespace {

void ClearAxes(QChart* chart) {
  for (QAbstractAxis* axis : chart->axes()) {
    chart->removeAxis(axis);
    delete axis;
  }
}

}  // namespace

QChartView* MakeChartView(const QString& title, const QString& x_title, const QString& y_title) {
  auto* chart = new QChart;
  chart->setTitle(title);
  chart->setProperty("x_title", x_title);
  chart->setProperty("y_title", y_title);
  chart->legend()->setAlignment(Qt::AlignBottom);
  auto* view = new QChartView(chart);
  view->setRenderHint(QPainter::Antialiasing);
  view->setMinimumHeight(200);
  return view;
}

void SetLines(QChartView* view, const std::vector<LineData>& lines, bool log_y) {
  QChart* chart = view->chart();
  chart->removeAllSeries();
  ClearAxes(chart);
  auto* x_values = new QValueAxis;
  x_values->setLabelFormat("%g");
  QAbstractAxis* x_axis = x_values;
  x_axis->setTitleText(chart->property("x_title").toString());
  QAbstractAxis* y_axis = nullptr;
  if (log_y) {
    auto* log_axis = new QLogValueAxis;
    log_axis->setLabelFormat("%.2g");
    y_axis = log_axis;
  } else {
    auto* value_axis = new QValueAxis;
    value_axis->setLabelFormat("%.3g");
    y_axis = value_axis;
  }
  y_axis->setTitleText(chart->property("y_title").toString());
  chart->addAxis(x_axis, Qt::AlignBottom);
  chart->addAxis(y_axis, Qt::AlignLeft);
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  for (const LineData& line : lines) {
    QXYSeries* series = line.markers ? static_cast<QXYSeries*>(new QScatterSeries) : new QLineSeries;
    if (line.markers) static_cast<QScatterSeries*>(series)->setMarkerSize(6);
    series->setName(line.name);
    for (const QPointF& p : line.points) {
      if (!std::isfinite(p.y()) || (log_y && p.y() <= 0)) continue;
      series->append(p);
      x_min = std::min(x_min, p.x()), x_max = std::max(x_max, p.x());
      y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
    }
    chart->addSeries(series);
    if (line.dashed) {
      QPen pen = series->pen();
      pen.setStyle(Qt::DashLine);
      series->setPen(pen);
    }
    series->attachAxis(x_axis);
    series->attachAxis(y_axis);
  }
  if (x_min > x_max) return;
  if (x_min == x_max) x_max = x_min + 1;
  const double pad = log_y ? 0 : 0.05 * std::max(y_max - y_min, 1e-12);
  x_axis->setRange(x_min, x_max);
  y_axis->setRange(log_y ? y_min / 1.5 : y_min - pad, log_y ? y_max * 1.5 : y_max + pad);
  // Round ticks (1, 2, 5 × 10^k) instead of the range split in equal parts.
  x_values->applyNiceNumbers();
  if (!log_y) static_cast<QValueAxis*>(y_axis)->applyNiceNumbers();
}

void AppendPoint(QChartView* view, int index, const QString& name, QPointF point) {
  QChart* chart = view->chart();
  if (chart->series().size() <= index) {
    SetLines(view, {LineData{name, {point}}});
    return;
  }
  auto* series = static_cast<QXYSeries*>(chart->series()[index]);
  series->append(point);
  auto* x_axis = static_cast<QValueAxis*>(chart->axes(Qt::Horizontal).front());
  auto* y_axis = static_cast<QValueAxis*>(chart->axes(Qt::Vertical).front());
  x_axis->setRange(std::min(x_axis->min(), point.x()), std::max(x_axis->max(), point.x()));
  y_axis->setRange(std::min(y_axis->min(), point.y()), std::max(y_axis->max(), point.y()));
}

void SetBars(QChartView* view, const QStringList& categories,
             const std::vector<std::pair<QString, std::vector<double>>>& sets) {
  QChart* chart = view->chart();
  chart->removeAllSeries();
  ClearAxes(chart);
  auto* series = new QBarSeries;
  double top = 0;
  for (const auto& [name, values] : sets) {
    auto* set = new QBarSet(name);
    for (double v : values) {
      *set << (std::isfinite(v) ? v : 0.0);
      if (std::isfinite(v)) top = std::max(top, v);
    }
    series->append(set);
  }
  chart->addSeries(series);
  auto* x_axis = new QBarCategoryAxis;
  x_axis->append(categories);
  x_axis->setTitleText(chart->property("x_title").toString());
  auto* y_axis = new QValueAxis;
  y_axis->setLabelFormat("%.3g");
  y_axis->setTitleText(chart->property("y_title").toString());
  y_axis->setRange(0, top > 0 ? 1.1 * top : 1);
  chart->addAxis(x_axis, Qt::AlignBottom);
  chart->addAxis(y_axis, Qt::AlignLeft);
  series->attachAxis(x_axis);
  series->attachAxis(y_axis);
}

}  // namespace hexcal::ui

#include "ui/charts.h"

#include <QBarCategoryAxis>
#include <QBarSeries>
#include <QBarSet>
#include <QCategoryAxis>
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

// Labels at round values (1, 2 or 5 × 10^k apart), each printed from an exact
// multiple of the step, so that zero reads "0" and not "-2.78e-17" (Qt's own
// ticks add the interval up from the minimum and carry its rounding).
void SetRoundTicks(QCategoryAxis* axis, double min, double max) {
  for (const QString& label : axis->categoriesLabels()) axis->remove(label);
  if (!(max > min)) max = min + 1;
  const double raw = (max - min) / 5;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double ratio = raw / power;
  const double step = (ratio <= 1 ? 1 : ratio <= 2 ? 2 : ratio <= 5 ? 5 : 10) * power;
  const long first = std::lround(std::floor(min / step)), last = std::lround(std::ceil(max / step));
  axis->setStartValue((first - 1e-6) * step);
  for (long k = first; k <= last; ++k) axis->append(QString::number(k * step, 'g', 6), k * step);
  axis->setLabelsPosition(QCategoryAxis::AxisLabelsPositionOnValue);
  axis->setRange(first * step, last * step);
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
  auto* x_values = new QCategoryAxis;
  QAbstractAxis* x_axis = x_values;
  x_axis->setTitleText(chart->property("x_title").toString());
  QAbstractAxis* y_axis = nullptr;
  if (log_y) {
    auto* log_axis = new QLogValueAxis;
    log_axis->setLabelFormat("%.2g");
    y_axis = log_axis;
  } else {
    y_axis = new QCategoryAxis;
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
  SetRoundTicks(x_values, x_min, x_max);
  if (log_y)
    y_axis->setRange(y_min / 1.5, y_max * 1.5);
  else
    SetRoundTicks(static_cast<QCategoryAxis*>(y_axis), y_min - pad, y_max + pad);
}

void AppendPoint(QChartView* view, int index, const QString& name, QPointF point) {
  QChart* chart = view->chart();
  if (chart->series().size() <= index) {
    SetLines(view, {LineData{name, {point}}});
    return;
  }
  auto* series = static_cast<QXYSeries*>(chart->series()[index]);
  series->append(point);
  auto* x_axis = qobject_cast<QCategoryAxis*>(chart->axes(Qt::Horizontal).front());
  if (x_axis) SetRoundTicks(x_axis, std::min(x_axis->min(), point.x()), std::max(x_axis->max(), point.x()));
  QAbstractAxis* y = chart->axes(Qt::Vertical).front();
  if (auto* y_axis = qobject_cast<QCategoryAxis*>(y))
    SetRoundTicks(y_axis, std::min(y_axis->min(), point.y()), std::max(y_axis->max(), point.y()));
  else if (auto* log_axis = qobject_cast<QLogValueAxis*>(y))
    log_axis->setRange(std::min(log_axis->min(), point.y()), std::max(log_axis->max(), point.y()));
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
  y_axis->applyNiceNumbers();  // ticks at 1, 2, 5 × 10^k
  chart->addAxis(x_axis, Qt::AlignBottom);
  chart->addAxis(y_axis, Qt::AlignLeft);
  series->attachAxis(x_axis);
  series->attachAxis(y_axis);
}

}  // namespace hexcal::ui

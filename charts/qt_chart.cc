#include "charts/qt_chart.h"

#include <QBarCategoryAxis>
#include <QBarSeries>
#include <QBarSet>
#include <QCategoryAxis>
#include <QChart>
#include <QGraphicsPathItem>
#include <QLegendMarker>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QPainterPath>
#include <QScatterSeries>
#include <algorithm>
#include <cassert>
#include <cmath>

using namespace QtCharts;

namespace hexcal::charts {
namespace {

// Paul Tol's "bright" palette: distinguishable, also by colour-blind readers
// and in grey print.
const char* const kPalette[] = {"#4477AA", "#EE6677", "#228833", "#CCBB44", "#66CCEE", "#AA3377", "#BBBBBB"};
constexpr int kPaletteSize = 7;
const char* const kLimitColour = "#555555";
const char* const kErrorColour = "#222222";
const char* const kMinorGridColour = "#f0f0f0";
constexpr int kMaxBarLabels = 12;     // more bars and their value labels overlap
constexpr int kMaxMarkedPoints = 60;  // more points on a line and markers hide it
constexpr int kPolylineItemKey = 0x68657863;  // QGraphicsItem::data key of the polyline paths ("hexc")

QColor SeriesColour(int k) { return QColor(kPalette[k % kPaletteSize]); }

// Qt Charts lays out titles, axis titles, labels and legend entries as rich
// text: "a < b" would lose everything after the '<'.
QString Q(const std::string& text) { return QString::fromStdString(text).toHtmlEscaped(); }

bool Drawable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

// Linear axes get their labels at the exact tick values of ComputeRanges
// (a QCategoryAxis, one category per tick), so that zero reads "0" and not
// "-2.78e-17" as Qt's own ticks, added up from the minimum, would.
void ApplyRange(QAbstractAxis* axis, const AxisRange& range) {
  if (auto* log = qobject_cast<QLogValueAxis*>(axis)) {
    // Qt counts the labelled decades from log(min) / log(10), which rounds to
    // -2.9999999999999996 for 0.001 and loses a label: widen by a hair.
    log->setRange(range.min * (1 - 1e-9), range.max * (1 + 1e-9));
    log->setMinorTickCount(range.ticks.size() <= 5 ? 8 : 0);  // 2..9 between few decades
    log->setMinorGridLinePen(QPen(QColor(kMinorGridColour), 1));
    return;
  }
  auto* ticks = qobject_cast<QCategoryAxis*>(axis);
  if (ticks == nullptr) return;
  for (const QString& label : ticks->categoriesLabels()) ticks->remove(label);
  ticks->setStartValue(range.min - 1e-6 * range.step);
  for (double tick : range.ticks) ticks->append(Q(TickLabel(tick, range.step)), tick);
  ticks->setLabelsPosition(QCategoryAxis::AxisLabelsPositionOnValue);
  ticks->setRange(range.min, range.max);
}

QAbstractAxis* NewValueAxis(const AxisSpec& spec, const AxisRange& range) {
  QAbstractAxis* axis = nullptr;
  if (range.log) {
    auto* log = new QLogValueAxis;
    log->setBase(10);
    log->setLabelFormat("%g");
    axis = log;
  } else {
    axis = new QCategoryAxis;
  }
  axis->setTitleText(Q(spec.label));
  axis->setReverse(spec.reversed);
  ApplyRange(axis, range);
  return axis;
}

void Style(QXYSeries* series, const SeriesSpec& spec, const QColor& colour) {
  if (auto* scatter = qobject_cast<QScatterSeries*>(series)) {
    scatter->setMarkerSize(7);
    scatter->setColor(colour);
    scatter->setBorderColor(colour);
    return;
  }
  QPen pen(spec.dashed ? QColor(kLimitColour) : colour);
  pen.setWidthF(spec.dashed ? 1.5 : 2);
  if (spec.dashed) pen.setStyle(Qt::DashLine);
  series->setPen(pen);
  series->setPointsVisible(!spec.dashed && spec.points.size() <= kMaxMarkedPoints);
}

// Qt Charts joins every point of a line series, and thousands of series (one
// per arrow) take seconds and megabytes of SVG: the pieces are one path item
// on the chart instead, placed through the axes whenever the plot area moves,
// and an empty line series with the same pen gives the legend entry.
void AddPolylines(QChart* chart, const ChartSpec& spec, const SeriesSpec& s, const QColor& colour,
                  QAbstractAxis* x_axis, QAbstractAxis* y_axis) {
  auto* legend = new QLineSeries;
  legend->setName(Q(s.name));
  chart->addSeries(legend);
  QPen pen(colour);
  pen.setWidthF(s.dashed ? 1 : 1.2);
  if (s.dashed) pen.setStyle(Qt::DashLine);
  legend->setPen(pen);
  legend->attachAxis(x_axis);
  legend->attachAxis(y_axis);
  auto* item = new QGraphicsPathItem(chart);
  item->setPen(pen);
  item->setData(kPolylineItemKey, true);
  const bool log_x = spec.x.log, log_y = spec.y.log;
  auto place = [chart, legend, item, points = s.points, log_x, log_y]() {
    QPainterPath path;
    bool start = true;
    for (const ChartPoint& p : points) {
      if (!Drawable(p.x, log_x) || !Drawable(p.y, log_y)) {
        start = true;
        continue;
      }
      const QPointF at = chart->mapToPosition(QPointF(p.x, p.y), legend);
      if (start) {
        path.moveTo(at);
      } else {
        path.lineTo(at);
      }
      start = false;
    }
    item->setPath(path);
  };
  QObject::connect(chart, &QChart::plotAreaChanged, legend, place);  // gone with the series
  place();
}

void AddXySeries(QChart* chart, const ChartSpec& spec, const ChartRanges& ranges) {
  QAbstractAxis* x_axis = NewValueAxis(spec.x, ranges.x);
  QAbstractAxis* y_axis = NewValueAxis(spec.y, ranges.y);
  chart->addAxis(x_axis, Qt::AlignBottom);
  chart->addAxis(y_axis, Qt::AlignLeft);
  int colour = 0;
  for (const SeriesSpec& s : spec.series) {
    if (s.kind == SeriesKind::kPolylines) {
      AddPolylines(chart, spec, s, s.dashed ? QColor(kLimitColour) : SeriesColour(colour++), x_axis, y_axis);
      continue;
    }
    QXYSeries* series = s.kind == SeriesKind::kScatter ? static_cast<QXYSeries*>(new QScatterSeries) : new QLineSeries;
    series->setName(Q(s.name));
    for (const ChartPoint& p : s.points) {
      if (Drawable(p.x, spec.x.log) && Drawable(p.y, spec.y.log)) series->append(p.x, p.y);
    }
    chart->addSeries(series);  // before styling: adding applies the theme's colours
    Style(series, s, s.dashed ? QColor(kLimitColour) : SeriesColour(colour++));
    series->attachAxis(x_axis);
    series->attachAxis(y_axis);
  }
}

// Qt Charts draws no error bars: one polyline per bar, top cap, stem, bottom
// cap, at the centre of the bar (Qt's layout: bar `set` of `sets` in category
// k spans k - width/2 + [set, set + 1] * width / sets).
void AddErrorBars(QChart* chart, const ChartSpec& spec, const ChartRanges& ranges, double bar_width,
                  QAbstractAxis* x_axis, QAbstractAxis* y_axis) {
  const int sets = static_cast<int>(spec.series.size());
  for (int set = 0; set < sets; ++set) {
    const SeriesSpec& s = spec.series[set];
    for (size_t k = 0; k < s.errors.size(); ++k) {
      const double value = s.values[k], error = s.errors[k];
      if (!Drawable(value, spec.y.log) || !(std::isfinite(error) && error > 0)) continue;
      const double centre = k - bar_width / 2 + (set + 0.5) * bar_width / sets, cap = 0.25 * bar_width / sets;
      const double top = value + error;
      const double bottom = Drawable(value - error, spec.y.log) ? value - error : ranges.y.min;  // log: cut
      auto* line = new QLineSeries;
      line->append({{centre - cap, top},
                    {centre + cap, top},
                    {centre, top},
                    {centre, bottom},
                    {centre - cap, bottom},
                    {centre + cap, bottom}});
      chart->addSeries(line);
      line->setPen(QPen(QColor(kErrorColour), 1.5));
      line->attachAxis(x_axis);
      line->attachAxis(y_axis);
      for (QLegendMarker* marker : chart->legend()->markers(line)) marker->setVisible(false);
    }
  }
}

bool HasErrorBarsOrNegativeBars(const ChartSpec& spec) {
  for (const SeriesSpec& s : spec.series) {
    for (double error : s.errors) {
      if (std::isfinite(error) && error > 0) return true;
    }
    for (double value : s.values) {
      if (value < 0) return true;
    }
  }
  return false;
}

void AddBars(QChart* chart, const ChartSpec& spec, const ChartRanges& ranges) {
  auto* x_axis = new QBarCategoryAxis;
  for (const std::string& category : spec.x.categories) x_axis->append(Q(category));
  x_axis->setTitleText(Q(spec.x.label));
  QAbstractAxis* y_axis = NewValueAxis(spec.y, ranges.y);
  chart->addAxis(x_axis, Qt::AlignBottom);
  chart->addAxis(y_axis, Qt::AlignLeft);
  auto* bars = new QBarSeries;
  if (spec.series.size() > 2) bars->setBarWidth(0.8);  // of a category: wider groups, fewer gaps
  for (const SeriesSpec& s : spec.series) {
    auto* set = new QBarSet(Q(s.name));
    // A value the axis cannot hold has no height: 0 (linear) or the bottom (log).
    for (double v : s.values) set->append(Drawable(v, spec.y.log) ? v : spec.y.log ? ranges.y.min : 0.0);
    bars->append(set);
  }
  chart->addSeries(bars);
  for (int k = 0; k < bars->count(); ++k) {
    bars->barSets()[k]->setColor(SeriesColour(k));
    bars->barSets()[k]->setBorderColor(SeriesColour(k));
    bars->barSets()[k]->setLabelColor(Qt::black);
  }
  if (bars->count() * static_cast<int>(spec.x.categories.size()) <= kMaxBarLabels) {
    bars->setLabelsVisible(true);
    bars->setLabelsFormat("@value");
    bars->setLabelsPrecision(3);
    // Above the bar an error bar would cross the label, and Qt puts the label
    // of a negative bar above zero: in the middle of the bar both read right.
    bars->setLabelsPosition(HasErrorBarsOrNegativeBars(spec) ? QAbstractBarSeries::LabelsCenter
                                                             : QAbstractBarSeries::LabelsOutsideEnd);
  }
  bars->attachAxis(x_axis);
  bars->attachAxis(y_axis);
  AddErrorBars(chart, spec, ranges, bars->barWidth(), x_axis, y_axis);
}

}  // namespace

QChart* NewQtChart(const ChartSpec& spec) {
  auto* chart = new QChart;
  chart->setAnimationOptions(QChart::NoAnimation);
  chart->setBackgroundRoundness(0);
  chart->setDropShadowEnabled(false);
  chart->legend()->setAlignment(Qt::AlignBottom);
  QFont title = chart->titleFont();
  title.setBold(true);
  chart->setTitleFont(title);
  FillQtChart(chart, spec);
  return chart;
}

void FillQtChart(QChart* chart, const ChartSpec& spec) {
  assert(spec.IsValid(nullptr));
  chart->removeAllSeries();
  for (QGraphicsItem* child : chart->childItems()) {
    if (child->data(kPolylineItemKey).toBool()) delete child;
  }
  for (QAbstractAxis* axis : chart->axes()) {
    chart->removeAxis(axis);
    delete axis;
  }
  chart->setTitle(Q(spec.title));
  const ChartRanges ranges = ComputeRanges(spec);
  if (spec.IsBarChart()) {
    AddBars(chart, spec, ranges);
  } else {
    AddXySeries(chart, spec, ranges);
  }
}

void AppendPoint(QChart* chart, ChartSpec* spec, int index, ChartPoint point) {
  assert(!spec->IsBarChart() && index >= 0 && index < static_cast<int>(spec->series.size()));
  spec->series[index].points.push_back(point);
  auto* series = qobject_cast<QXYSeries*>(chart->series().value(index));
  const QList<QAbstractAxis*> x_axes = chart->axes(Qt::Horizontal), y_axes = chart->axes(Qt::Vertical);
  // Polylines are path items beside their series: redrawn whole.
  const bool polylines = std::any_of(spec->series.begin(), spec->series.end(),
                                     [](const SeriesSpec& s) { return s.kind == SeriesKind::kPolylines; });
  if (series == nullptr || polylines || x_axes.isEmpty() || y_axes.isEmpty())
    return FillQtChart(chart, *spec);  // not spec's
  if (Drawable(point.x, spec->x.log) && Drawable(point.y, spec->y.log)) series->append(point.x, point.y);
  if (auto* line = qobject_cast<QLineSeries*>(series))
    Style(line, spec->series[index], line->color());  // markers off past kMaxMarkedPoints
  const ChartRanges ranges = ComputeRanges(*spec);
  ApplyRange(x_axes.front(), ranges.x);
  ApplyRange(y_axes.front(), ranges.y);
}

}  // namespace hexcal::charts

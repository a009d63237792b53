// The Qt chart of a spec: its axes are ComputeRanges(spec) (so the negative
// bars the figure tests check are on screen), its series are the spec's, and
// live appends widen the axes.
#include "charts/qt_chart.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <QApplication>
#include <QBarCategoryAxis>
#include <QBarSeries>
#include <QBarSet>
#include <QCategoryAxis>
#include <QChart>
#include <QGraphicsPathItem>
#include <QGraphicsScene>
#include <QLegendMarker>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QPainterPath>
#include <QScatterSeries>
#include <cmath>
#include <memory>

#include "charts/figures.h"

namespace hexcal::charts {
namespace {

using namespace QtCharts;

// Charts are QGraphicsWidgets: a QApplication must exist (offscreen: CTest sets QT_QPA_PLATFORM).
void EnsureApplication() {
  static int argc = 1;
  static char name[] = "qt_chart_test";
  static char* argv[] = {name, nullptr};
  if (QCoreApplication::instance() == nullptr) new QApplication(argc, argv);  // lives until exit
}

class QtChartTest : public ::testing::Test {
 protected:
  void SetUp() override { EnsureApplication(); }
};

QAbstractAxis* Axis(QChart* chart, Qt::Orientation orientation) {
  const QList<QAbstractAxis*> axes = chart->axes(orientation);
  EXPECT_EQ(axes.size(), 1);
  return axes.value(0);
}

// The range the axis draws, whatever its kind.
std::pair<double, double> Drawn(QAbstractAxis* axis) {
  if (auto* ticks = qobject_cast<QCategoryAxis*>(axis)) return {ticks->min(), ticks->max()};
  if (auto* log = qobject_cast<QLogValueAxis*>(axis)) return {log->min(), log->max()};
  ADD_FAILURE() << "unexpected axis type";
  return {0, 0};
}

// The axis draws `range` (a log axis a hair wider, see qt_chart.cc).
void ExpectDrawn(QAbstractAxis* axis, const AxisRange& range) {
  const auto [min, max] = Drawn(axis);
  EXPECT_NEAR(min, range.min, 1e-8 * std::abs(range.min));
  EXPECT_NEAR(max, range.max, 1e-8 * std::abs(range.max));
  EXPECT_LE(min, range.min);
  EXPECT_GE(max, range.max);
}

TEST_F(QtChartTest, NegativeBarsAreOnTheValueAxisWithTheirErrorBars) {
  const ChartSpec spec =
      ParameterChangeChart({{1, "a_x", 0.12, 0.03}, {1, "a_y", -0.4, 0.05}, {1, "l", -0.02, 0}}, "mm");
  std::unique_ptr<QChart> chart(NewQtChart(spec));
  const ChartRanges ranges = ComputeRanges(spec);
  ExpectDrawn(Axis(chart.get(), Qt::Vertical), ranges.y);
  EXPECT_LT(Drawn(Axis(chart.get(), Qt::Vertical)).first, -0.45);
  auto* x_axis = qobject_cast<QBarCategoryAxis*>(Axis(chart.get(), Qt::Horizontal));
  ASSERT_NE(x_axis, nullptr);
  EXPECT_EQ(x_axis->categories(), QStringList({"a_x", "a_y", "l"}));
  auto* bars = qobject_cast<QBarSeries*>(chart->series().value(0));
  ASSERT_NE(bars, nullptr);
  ASSERT_EQ(bars->count(), 1);
  EXPECT_DOUBLE_EQ(bars->barSets()[0]->at(1), -0.4);
  // Two error bars (sigma 0 has none), each a polyline reaching value ± sigma, out of the legend.
  ASSERT_EQ(chart->series().size(), 3);
  auto* error = qobject_cast<QLineSeries*>(chart->series()[2]);
  ASSERT_NE(error, nullptr);
  double lowest = 1e9;
  for (const QPointF& p : error->points()) lowest = std::min(lowest, p.y());
  EXPECT_DOUBLE_EQ(lowest, -0.45);
  QGraphicsScene scene;
  scene.addItem(chart.get());
  chart->setGeometry(0, 0, 900, 460);
  QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
  std::fprintf(stderr, "markers: error %d bars %d, legend %d\n", chart->legend()->markers(error).value(0)->isVisible(),
               chart->legend()->markers(bars).value(0)->isVisible(), chart->legend()->isVisible());
  scene.removeItem(chart.get());
  EXPECT_FALSE(chart->legend()->markers(error).value(0)->isVisible());
  EXPECT_TRUE(chart->legend()->markers(bars).value(0)->isVisible());
}

TEST_F(QtChartTest, LineChartDrawsThePointsTheLogAxisCanHold) {
  ChartSpec spec;
  spec.title = "indices";
  spec.y.log = true;
  spec.series = {LineSeries("O1", {{0, 1.5}, {1, 0}, {2, 2.5}}), LineSeries("limit", {{0, 2}, {2, 2}}, true),
                 ScatterSeries("dots", {{1, 0.01}})};
  std::unique_ptr<QChart> chart(NewQtChart(spec));
  EXPECT_EQ(chart->title(), "indices");
  ASSERT_EQ(chart->series().size(), 3);
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[0])->count(), 2);  // 0 is not on a log axis
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[1])->pen().style(), Qt::DashLine);
  EXPECT_NE(qobject_cast<QScatterSeries*>(chart->series()[2]), nullptr);
  const ChartRanges ranges = ComputeRanges(spec);
  ExpectDrawn(Axis(chart.get(), Qt::Vertical), ranges.y);
  ExpectDrawn(Axis(chart.get(), Qt::Horizontal), ranges.x);
  // The linear x axis is labelled at its ticks, exactly.
  auto* x_axis = qobject_cast<QCategoryAxis*>(Axis(chart.get(), Qt::Horizontal));
  ASSERT_NE(x_axis, nullptr);
  EXPECT_EQ(x_axis->count(), static_cast<int>(ranges.x.ticks.size()));
  EXPECT_TRUE(x_axis->categoriesLabels().contains("0"));
}

// Arrows and grid lines: one path of separate pieces (a Qt line series would
// join them), placed through the axes, with one legend entry; image rows grow
// downwards on a reversed axis.
TEST_F(QtChartTest, PolylinesAreOnePathOfPiecesWithOneLegendEntry) {
  ChartSpec spec;
  spec.y.reversed = true;
  spec.series = {PolylineSeries("arrows", {{{0, 0}, {1, 1}}, {{5, 5}, {6, 5}, {6, 6}}, {{9, 0}, {9, 1}}}),
                 LineSeries("line", {{0, 2}, {9, 2}})};
  std::unique_ptr<QChart> chart(NewQtChart(spec));
  ASSERT_EQ(chart->series().size(), 2);
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[0])->count(), 0);  // the legend entry only
  QGraphicsScene scene;
  scene.addItem(chart.get());
  chart->setGeometry(0, 0, 600, 400);
  QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
  std::vector<QGraphicsPathItem*> paths;
  for (QGraphicsItem* child : chart->childItems())
    if (auto* path = dynamic_cast<QGraphicsPathItem*>(child)) paths.push_back(path);
  ASSERT_EQ(paths.size(), 1u);
  const QPainterPath& path = paths[0]->path();
  ASSERT_EQ(path.elementCount(), 7);  // 3 pieces: 3 moves, 4 lines
  int moves = 0;
  for (int k = 0; k < path.elementCount(); ++k) moves += path.elementAt(k).isMoveTo();
  EXPECT_EQ(moves, 3);
  // Placed where the axes put the data: (5, 5) is where the line series would draw it.
  const QPointF expected = chart->mapToPosition({5, 5}, chart->series()[1]);
  EXPECT_NEAR(path.elementAt(2).x, expected.x(), 1e-9);
  EXPECT_NEAR(path.elementAt(2).y, expected.y(), 1e-9);
  // Reversed: y = 0 is at the top of the plot, y = 6 lower down.
  EXPECT_LT(chart->mapToPosition({0, 0}, chart->series()[1]).y(), chart->mapToPosition({0, 6}, chart->series()[1]).y());
  EXPECT_TRUE(Axis(chart.get(), Qt::Vertical)->isReverse());
  EXPECT_FALSE(Axis(chart.get(), Qt::Horizontal)->isReverse());
  // A live append on such a chart redraws it whole, and the old path goes.
  AppendPoint(chart.get(), &spec, 1, {10, 2});
  int items = 0;
  for (QGraphicsItem* child : chart->childItems()) items += dynamic_cast<QGraphicsPathItem*>(child) != nullptr;
  EXPECT_EQ(items, 1);
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[1])->count(), 3);
  scene.removeItem(chart.get());
}

TEST_F(QtChartTest, AppendPointWidensTheAxesAsThePlannerRuns) {
  ChartSpec spec = ObservabilityChart({});
  std::unique_ptr<QChart> chart(NewQtChart(spec));
  AppendPoint(chart.get(), &spec, 0, {0, 1.5});
  AppendPoint(chart.get(), &spec, 2, {0, 3e-4});
  AppendPoint(chart.get(), &spec, 0, {40, 7.5});
  AppendPoint(chart.get(), &spec, 1, {41, 0});  // kept in the spec, not drawn on the log axis
  EXPECT_EQ(spec.series[0].points.size(), 2u);
  EXPECT_EQ(spec.series[1].points.size(), 1u);
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[0])->count(), 2);
  EXPECT_EQ(qobject_cast<QLineSeries*>(chart->series()[1])->count(), 0);
  const auto [y_min, y_max] = Drawn(Axis(chart.get(), Qt::Vertical));
  EXPECT_LE(y_min, 3e-4);
  EXPECT_GE(y_max, 7.5);
  const auto [x_min, x_max] = Drawn(Axis(chart.get(), Qt::Horizontal));
  EXPECT_LE(x_min, 0);
  EXPECT_GE(x_max, 40);
  ExpectDrawn(Axis(chart.get(), Qt::Horizontal), ComputeRanges(spec).x);
  ExpectDrawn(Axis(chart.get(), Qt::Vertical), ComputeRanges(spec).y);
  // A long run: the line drops its point markers, as a chart built whole would.
  auto* o1 = qobject_cast<QLineSeries*>(chart->series()[0]);
  EXPECT_TRUE(o1->pointsVisible());
  for (int i = 41; i < 200; ++i) AppendPoint(chart.get(), &spec, 0, {1.0 * i, 7.5});
  EXPECT_FALSE(o1->pointsVisible());
}

TEST_F(QtChartTest, FillReplacesSeriesAndAxes) {
  std::unique_ptr<QChart> chart(NewQtChart(ParameterChangeChart({{1, "a_x", 0.1, 0.01}}, "mm")));
  FillQtChart(chart.get(), MeasurementRmsChart({0.1, 0.2}));
  EXPECT_EQ(chart->title(), "Measurement quality");
  ASSERT_EQ(chart->series().size(), 1);
  EXPECT_NE(qobject_cast<QLineSeries*>(chart->series()[0]), nullptr);
  EXPECT_EQ(chart->axes().size(), 2);
}

}  // namespace
}  // namespace hexcal::charts

// The per-corner diagnostics as the report draws and names them: the residual
// field of a known distortion error, the CSV round trip, the JSON figures.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report/corner_charts.h"
#include "report/corner_report_section.h"
#include "tests/test_support.h"
#include "vision/camera.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

Camera Pinhole(double k1) {
  Camera camera;
  camera.width = 1024;
  camera.height = 768;
  camera.fx = camera.fy = 800;
  camera.cx = 512;
  camera.cy = 384;
  camera.model = CameraModel::kRadTan;
  camera.distortion[0] = k1;
  return camera;
}

// Corners seen through a lens with k1 = -0.2 (barrel), reprojected by a model
// without distortion: the residual is -f k1 |p|² p for the normalised point
// p (camera.h's radial term), outwards from the centre and growing as r³.
TEST(CornerReportTest, AMissingBarrelDistortionDrawsArrowsOutwardsGrowingWithRadius) {
  const double k1 = -0.2, f = 800;
  const Camera lens = Pinhole(k1), model = Pinhole(0);
  std::vector<CornerResidual> corners;
  std::vector<Eigen::Vector2d> normalised;
  for (double x = -0.55; x <= 0.56; x += 0.1) {
    for (double y = -0.4; y <= 0.41; y += 0.1) {
      const Eigen::Vector3d ray(x, y, 1);
      const Eigen::Vector2d observed = lens.Project(ray);
      corners.push_back({0, 0, 0, observed, model.Project(ray) - observed});
      normalised.emplace_back(x, y);
    }
  }
  const charts::ChartSpec spec = ResidualFieldChart(corners, 1024, 768);
  ASSERT_TRUE(spec.IsValid(nullptr));
  ASSERT_EQ(spec.series.size(), 2u);  // the image frame, the arrows
  const charts::SeriesSpec& arrows = spec.series[1];
  ASSERT_EQ(arrows.kind, charts::SeriesKind::kPolylines);
  ASSERT_EQ(arrows.points.size(), 6 * corners.size());  // tail, tip, barb, tip, barb, break
  const double scale = ResidualArrowScale(corners, 1024);
  char scale_text[32];
  std::snprintf(scale_text, sizeof scale_text, scale >= 1 ? "%.0f" : "%.3g", scale);
  EXPECT_THAT(spec.title, HasSubstr(std::string("arrows × ") + scale_text));
  for (size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d p = normalised[i];
    const Eigen::Vector2d expected = -f * k1 * p.squaredNorm() * p;  // pixels, outwards for k1 < 0
    const charts::ChartPoint tail = arrows.points[6 * i], tip = arrows.points[6 * i + 1];
    EXPECT_NEAR(tail.x, 512 + f * p.x() * (1 + k1 * p.squaredNorm()), 1e-9);
    EXPECT_NEAR(tip.x - tail.x, scale * expected.x(), 1e-6) << i;
    EXPECT_NEAR(tip.y - tail.y, scale * expected.y(), 1e-6) << i;
  }
  // The scale: the 95th-percentile arrow between 1.6 % and 4 % of the width (1, 2, 5 steps).
  std::vector<double> norms;
  for (const CornerResidual& c : corners) norms.push_back(c.residual.norm());
  std::sort(norms.begin(), norms.end());
  const double p95 = scale * norms[static_cast<size_t>(0.95 * (norms.size() - 1))];
  EXPECT_LE(p95, 0.04 * 1024 + 1e-9);
  EXPECT_GT(p95, 0.016 * 1024);
}

CornerResidualTable SmallTable() {
  CornerResidualTable table;
  table.images = {"a.png", "b,1.png"};
  table.corners = {{0, 3, 0, {10, 20}, {0.1, 0}},
                   {1, 7, 2, {630, 470}, {0, -2.5}},
                   {1, 7, 3, {600, 470}, {0.3, 0.4}},
                   {0, 4, 1, {15, 25}, {-0.05, 0.05}}};
  return table;
}

TEST(CornerReportTest, ResidualsFileRoundTripsAndNamesABadLine) {
  TempDir dir;
  const CornerResidualTable table = SmallTable();
  ASSERT_TRUE(SaveCornerResiduals(dir.File("c.csv"), table).ok());
  StatusOr<CornerResidualTable> read = LoadCornerResiduals(dir.File("c.csv"));
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->images, table.images);
  ASSERT_EQ(read->corners.size(), table.corners.size());
  for (size_t i = 0; i < table.corners.size(); ++i) {
    EXPECT_EQ(read->corners[i].image, table.corners[i].image);
    EXPECT_EQ(read->corners[i].tag_id, table.corners[i].tag_id);
    EXPECT_EQ(read->corners[i].corner, table.corners[i].corner);
    EXPECT_EQ(read->corners[i].observed, table.corners[i].observed);
    EXPECT_EQ(read->corners[i].residual, table.corners[i].residual);
  }
  WriteTextFile(dir.File("bad.csv"), "image,tag_id,corner,x_px,y_px,dx_px,dy_px\na.png,1.5,0,1,2,3,4\n");
  EXPECT_THAT(LoadCornerResiduals(dir.File("bad.csv")).status().message(),
              HasSubstr("bad.csv:2: column 'tag_id': not a whole number"));
}

TEST(CornerReportTest, JsonNamesTheWorstCornersAndCountsBinsAndCells) {
  const nlohmann::json json = CornerDiagnosticsJson(SmallTable(), 640, 480);
  EXPECT_EQ(json["corners"], 4);
  ASSERT_EQ(json["worst"].size(), 4u);
  EXPECT_EQ(json["worst"][0]["image"], "b,1.png");
  EXPECT_EQ(json["worst"][0]["tag_id"], 7);
  EXPECT_EQ(json["worst"][0]["corner"], 2);
  EXPECT_DOUBLE_EQ(json["worst"][0]["residual_px"], 2.5);
  EXPECT_DOUBLE_EQ(json["worst"][1]["residual_px"], 0.5);
  // Median |r| of 0.0707, 0.1, 0.5, 2.5 is 0.3: σ = 0.3 / √(2 ln 2); 2.5 px is past 6σ.
  const double sigma = 0.3 / std::sqrt(2 * std::log(2.0));
  EXPECT_NEAR(json["sigma_px"], sigma, 1e-12);
  EXPECT_EQ(json["histogram"]["counts"].size(), 12u);
  EXPECT_EQ(json["histogram"]["beyond"], 1);
  EXPECT_NEAR(json["histogram"]["bin_width_px"], sigma / 2, 1e-12);
  EXPECT_EQ(json["coverage"]["counts"][0], 2);   // top left 80 × 80 cell
  EXPECT_EQ(json["coverage"]["counts"][47], 2);  // bottom right
  EXPECT_EQ(json["coverage"]["empty_cells"], 46);
  EXPECT_THAT(FormatWorstCorners(SmallTable(), 1), HasSubstr("b,1.png tag 7 corner 2 at (630.0, 470.0): 2.5 px"));
  EXPECT_EQ(FormatCornerFigures(SmallTable(), 640, 480),
            "4 corners, RMS 1.28 px, sigma 0.255 px (from the median); 1 at 3 sigma or more (noise alone: 0.0444); "
            "46 of 48 image cells without a corner");
}

TEST(CornerReportTest, HistogramChartHasABarPairPerBinAndOneBeyond) {
  const ResidualHistogram h = HistogramOfResiduals(SmallTable().corners, 0.2, 12);
  const charts::ChartSpec spec = ResidualHistogramChart(h);
  ASSERT_TRUE(spec.IsValid(nullptr));
  const std::vector<std::string> expected = {"0", "½", "1", "1½", "2", "2½", "3", "3½", "4", "4½", "5", "5½", "≥6"};
  EXPECT_EQ(spec.x.categories, expected);
  ASSERT_EQ(spec.series.size(), 2u);
  EXPECT_EQ(spec.series[0].values.back(), h.beyond);
  EXPECT_EQ(spec.series[1].values.front(), h.expected.front());
}

TEST(CornerReportTest, SectionHoldsTheChartsTheWorstTableAndTheEmptyCells) {
  const std::string html = CornerDiagnosticsSection(SmallTable(), 640, 480);
  size_t charts = 0;
  for (size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++charts;
  EXPECT_EQ(charts, 3u);
  EXPECT_NE(html.find("<h2>Per-corner diagnostics</h2>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>b,1.png</td><td>7</td><td>2</td>"), std::string::npos);
  EXPECT_NE(html.find("46 empty cells"), std::string::npos);
  // |r| ≥ 3σ = 0.764 px: the 2.5 px corner only; noise alone 4 exp(−4.5) = 0.0444.
  EXPECT_NE(html.find("Corners at 3&sigma; or more: 1 (noise of &sigma; alone: 0.0444)"), std::string::npos);
  EXPECT_EQ(CornerDiagnosticsSection({}, 640, 480), "");
}

}  // namespace
}  // namespace hexcal::workflow

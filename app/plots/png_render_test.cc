// SVG to PNG without a display: the file is a PNG of the requested size with
// the chart's ink on it, and invalid SVG is an error.
#include "app/plots/png_render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <QColor>
#include <QImage>

#include "app/plots/svg_chart.h"
#include "tests/test_support.h"

namespace hexcal::plots {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::testing::HasSubstr;

TEST(PngRender, WritesAPngOfTheChart) {
  TempDir dir;
  ChartOptions options;
  options.title = "test";
  const std::string path = dir.File("chart.png");
  const Status written = WriteSvgAsPng(BarChartSvg(options, {{"a", 1, 0.2}, {"b", 2, 0}}), path, 380, 230);
  ASSERT_TRUE(written.ok()) << written.message();
  EXPECT_EQ(ReadTextFile(path).substr(0, 8), "\x89PNG\r\n\x1a\n");
  const QImage image(QString::fromStdString(path));
  ASSERT_FALSE(image.isNull());
  EXPECT_EQ(image.width(), 380);
  EXPECT_EQ(image.height(), 230);
  int coloured = 0;  // the bars: the palette's blue and red
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) coloured += QColor(image.pixel(x, y)).saturation() > 100;
  }
  EXPECT_GT(coloured, 1000);
  // A second render in the same process works too.
  EXPECT_TRUE(WriteSvgAsPng(BarChartSvg(options, {{"a", 1, 0}}), dir.File("again.png"), 100, 80).ok());
}

TEST(PngRender, InvalidSvgIsAnError) {
  TempDir dir;
  const Status written = WriteSvgAsPng("<svg", dir.File("bad.png"), 100, 100);
  ASSERT_FALSE(written.ok());
  EXPECT_THAT(written.message(), HasSubstr("not valid SVG"));
}

}  // namespace
}  // namespace hexcal::plots

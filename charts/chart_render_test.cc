// Offscreen rendering with no display: SVG that parses and carries the title
// and the series, PNG of the requested size with the series' ink on it, both
// files written by WriteChartFiles, and a refusal off the Qt thread.
#include "charts/chart_render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <QColor>
#include <QGuiApplication>
#include <QImage>
#include <QXmlStreamReader>
#include <thread>

#include "charts/figures.h"
#include "tests/test_support.h"

namespace hexcal::charts {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

ChartSpec TwoLines() {
  ChartSpec spec;
  spec.title = "a < b & c";
  spec.x.label = "number of poses";
  spec.y = LogAxis("error (mm)");
  spec.series = {LineSeries("random", {{8, 0.3}, {9, 0.1}, {10, 0.05}}),
                 LineSeries("boundary", {{8, 0.01}, {9, 0.004}})};
  return spec;
}

struct ParsedSvg {
  QString error;              // empty when the document is well-formed
  int empty_groups = 0;       // <g> elements with nothing inside
  QString root;               // the first element's name
  QString width, height;      // its attributes
  QStringList texts;          // the text of every <text> element
  QString strokes_and_fills;  // every stroke and fill colour, lower case
};

ParsedSvg Parse(const std::string& svg) {
  ParsedSvg parsed;
  QXmlStreamReader xml(QByteArray::fromStdString(svg));
  bool group_open = false;  // the last element opened is a <g> with nothing in it yet
  while (!xml.atEnd()) {
    const QXmlStreamReader::TokenType token = xml.readNext();
    if (token == QXmlStreamReader::EndElement && xml.name() == QLatin1String("g") && group_open) ++parsed.empty_groups;
    if (token == QXmlStreamReader::StartElement || token == QXmlStreamReader::EndElement) {
      group_open = token == QXmlStreamReader::StartElement && xml.name() == QLatin1String("g");
    }
    if (token != QXmlStreamReader::StartElement) continue;
    if (parsed.root.isEmpty()) {
      parsed.root = xml.name().toString();
      parsed.width = xml.attributes().value("width").toString();
      parsed.height = xml.attributes().value("height").toString();
    }
    for (const char* key : {"stroke", "fill"})
      parsed.strokes_and_fills += xml.attributes().value(key).toString().toLower() + " ";
    if (xml.name() == QLatin1String("text"))
      parsed.texts << xml.readElementText(QXmlStreamReader::IncludeChildElements).trimmed();
  }
  if (xml.hasError()) parsed.error = xml.errorString();
  return parsed;
}

// Pixels of a strongly coloured ink (the palette; not the black, grey or white of text and grid).
int Coloured(const QImage& image, const QColor& near) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const QColor c(image.pixel(x, y));
      count +=
          std::abs(c.red() - near.red()) + std::abs(c.green() - near.green()) + std::abs(c.blue() - near.blue()) < 40;
    }
  }
  return count;
}

TEST(ChartRender, SvgParsesAndHoldsTheTitleAxesAndEverySeries) {
  StatusOr<std::string> svg = ChartSvg(TwoLines());
  ASSERT_TRUE(svg.ok()) << svg.status().message();
  EXPECT_THAT(*svg, StartsWith("<?xml"));
  const ParsedSvg parsed = Parse(*svg);
  ASSERT_TRUE(parsed.error.isEmpty()) << parsed.error.toStdString();
  EXPECT_EQ(parsed.root, "svg");
  EXPECT_EQ(parsed.width, "760");
  EXPECT_EQ(parsed.height, "460");
  for (const char* text : {"a < b & c", "number of poses", "error (mm)", "random", "boundary"}) {
    EXPECT_TRUE(parsed.texts.contains(text)) << text << " not in " << parsed.texts.join(" | ").toStdString();
  }
  // Both lines are drawn, in the first two colours of the palette.
  EXPECT_THAT(parsed.strokes_and_fills.toStdString(), HasSubstr("#4477aa"));
  EXPECT_THAT(parsed.strokes_and_fills.toStdString(), HasSubstr("#ee6677"));
  EXPECT_EQ(parsed.empty_groups, 0);               // QSvgGenerator's empty state groups are dropped
  EXPECT_THAT(*svg, HasSubstr(", sans-serif\""));  // a browser without Qt's font still draws sans
  // It is drawn on the offscreen platform: no display was needed.
  EXPECT_EQ(QGuiApplication::platformName(), "offscreen");
}

TEST(ChartRender, SvgElementIsTheBareSvgForAnHtmlPage) {
  StatusOr<std::string> svg = ChartSvgElement(ParameterChangeChart({{1, "a_x", -0.2, 0.05}}, "mm"));
  ASSERT_TRUE(svg.ok()) << svg.status().message();
  EXPECT_THAT(*svg, StartsWith("<svg"));
  EXPECT_THAT(*svg, HasSubstr("width=\"900\""));
  EXPECT_TRUE(Parse(*svg).error.isEmpty());
  EXPECT_TRUE(Parse(*svg).texts.contains("Calibrated minus nominal, with 1 sigma"));
}

// 42 parameters under a 900 px chart: every label is drawn in full.
TEST(ChartRender, EveryParameterLabelIsReadable) {
  std::vector<ParameterChange> changes;
  for (int leg = 1; leg <= 6; ++leg) {
    for (const char* name : {"a_x", "a_y", "a_z", "b_x", "b_y", "b_z", "l"}) changes.push_back({leg, name, -0.1, 0.01});
  }
  StatusOr<std::string> svg = ChartSvg(ParameterChangeChart(changes, "cm"));
  ASSERT_TRUE(svg.ok()) << svg.status().message();
  const ParsedSvg parsed = Parse(*svg);
  EXPECT_FALSE(parsed.texts.contains("...")) << parsed.texts.join(" | ").toStdString();
  for (const char* label : {"a_x", "b_z", "l", "leg 1", "leg 6"}) EXPECT_TRUE(parsed.texts.contains(label)) << label;
}

TEST(ChartRender, PngOfTheRequestedSizeWithTheSeriesInk) {
  ChartSpec spec = TwoLines();
  spec.width = 380;
  spec.height = 230;
  StatusOr<std::string> png = ChartPng(spec);
  ASSERT_TRUE(png.ok()) << png.status().message();
  EXPECT_EQ(png->substr(0, 8), "\x89PNG\r\n\x1a\n");
  const QImage image = QImage::fromData(QByteArray::fromStdString(*png), "PNG");
  ASSERT_FALSE(image.isNull());
  EXPECT_EQ(image.width(), 380);
  EXPECT_EQ(image.height(), 230);
  EXPECT_GT(Coloured(image, QColor("#4477AA")), 50);
  EXPECT_GT(Coloured(image, QColor("#EE6677")), 30);
}

// The bug of the hand-written SVG chart: a negative bar drawn as nothing.
// The second category is the right half of the plot; its bar must have ink.
TEST(ChartRender, NegativeBarsHaveInk) {
  const auto right_half_ink = [](double second) {
    StatusOr<std::string> png = ChartPng(ParameterChangeChart({{1, "a_x", 1, 0}, {1, "a_y", second, 0}}, "mm"));
    EXPECT_TRUE(png.ok());
    const QImage image = QImage::fromData(QByteArray::fromStdString(*png), "PNG");
    return Coloured(image.copy(image.width() / 2, 0, image.width() / 2, image.height()), QColor("#4477AA"));
  };
  EXPECT_LT(right_half_ink(0), 100);
  EXPECT_GT(right_half_ink(-1), 10000);
}

TEST(ChartRender, WritesTheSvgAndThePngFiles) {
  TempDir dir;
  std::vector<std::string> written;
  const Status s = WriteChartFiles(TwoLines(), dir.path().string(), "fig15_mean", &written);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0], dir.File("fig15_mean.svg"));
  EXPECT_EQ(written[1], dir.File("fig15_mean.png"));
  EXPECT_THAT(ReadTextFile(written[0]), HasSubstr("</svg>"));
  EXPECT_EQ(ReadTextFile(written[1]).substr(0, 4), "\x89PNG");
  const Status missing = WriteChartFiles(TwoLines(), dir.File("no/such/folder"), "fig14", &written);
  EXPECT_FALSE(missing.ok());
  EXPECT_THAT(missing.message(), HasSubstr("no/such/folder/fig14.svg"));
}

TEST(ChartRender, AnInvalidSpecIsAnError) {
  ChartSpec spec;
  spec.title = "broken";
  spec.x.categories = {"a", "b"};
  spec.series.push_back(BarSeries("v", {1}));
  StatusOr<std::string> svg = ChartSvg(spec);
  ASSERT_FALSE(svg.ok());
  EXPECT_THAT(svg.status().message(), HasSubstr("chart 'broken'"));
}

TEST(ChartRender, AWorkerThreadGetsAnErrorNotACrash) {
  ASSERT_TRUE(ChartSvg(TwoLines()).ok());  // the QApplication now belongs to this thread
  Status status;
  std::thread worker([&] { status = ChartPng(TwoLines()).status(); });
  worker.join();
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("thread"));
}

}  // namespace
}  // namespace hexcal::charts

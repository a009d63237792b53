#include "app/plots/svg_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>

namespace hexcal::plots {
namespace {

// Paul Tol's "bright" palette: distinguishable, also in grey print.
const char* const kColours[] = {"#4477AA", "#EE6677", "#228833", "#CCBB44", "#66CCEE", "#AA3377", "#BBBBBB"};
constexpr int kNumColours = 7;
constexpr double kLeft = 86, kRight = 24, kTop = 48, kBottom = 64;  // plot-area margins, px

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Format(double v, const char* format = "%g") {
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// A value axis: maps data to pixels, linear or log10.
struct Axis {
  double lo = 0, hi = 1;  // data range (log: both > 0)
  bool log = false;
  double pixel_lo = 0, pixel_hi = 1;

  double ToPixel(double v) const {
    double t;
    if (log) {
      v = std::max(v, lo);
      t = (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    } else {
      t = (v - lo) / (hi - lo);
    }
    return pixel_lo + t * (pixel_hi - pixel_lo);
  }

  std::vector<double> Ticks() const {
    if (!log) return LinearTicks(lo, hi);
    std::vector<double> ticks;
    const int first = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
    const int last = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
    const bool minor = last - first <= 2;  // few decades: label 2 and 5 as well
    for (int e = first; e <= last; ++e) {
      for (double m : {1.0, 2.0, 5.0}) {
        if (m != 1.0 && !minor) continue;
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
      }
    }
    return ticks;
  }
};

Axis ValueAxis(double lo, double hi, bool log, double pixel_bottom, double pixel_top) {
  Axis axis;
  axis.log = log;
  axis.pixel_lo = pixel_bottom;
  axis.pixel_hi = pixel_top;
  if (log) {
    if (!(hi > 0)) hi = 1;
    if (!(lo > 0) || lo >= hi) lo = hi / 10;
    axis.lo = std::pow(10.0, std::floor(std::log10(lo)));
    axis.hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (axis.hi <= axis.lo) axis.hi = axis.lo * 10;
  } else {
    if (!(hi > lo)) hi = lo + 1;
    const std::vector<double> ticks = LinearTicks(lo, hi);
    axis.lo = std::min(lo, ticks.front());
    axis.hi = std::max(hi, ticks.back());
  }
  return axis;
}

class SvgWriter {
 public:
  explicit SvgWriter(const ChartOptions& options) : options_(options) {
    out_ << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << options.width << "\" height=\"" << options.height
         << "\" viewBox=\"0 0 " << options.width << " " << options.height
         << "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"13\">\n"
         << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    Text(options.width / 2.0, 26, options.title, "middle", 16, "bold");
  }

  double PlotLeft() const { return kLeft; }
  double PlotRight() const { return options_.width - kRight; }
  double PlotTop() const { return kTop; }
  double PlotBottom() const { return options_.height - kBottom; }

  void Text(double x, double y, const std::string& text, const char* anchor = "middle", int size = 13,
            const char* weight = "normal", const std::string& transform = "") {
    out_ << "<text x=\"" << Format(x, "%.1f") << "\" y=\"" << Format(y, "%.1f") << "\" text-anchor=\"" << anchor
         << "\" font-size=\"" << size << "\" font-weight=\"" << weight << "\"";
    if (!transform.empty()) out_ << " transform=\"" << transform << "\"";
    out_ << ">" << Escape(text) << "</text>\n";
  }

  void Line(double x1, double y1, double x2, double y2, const char* colour, double width = 1) {
    out_ << "<line x1=\"" << Format(x1, "%.1f") << "\" y1=\"" << Format(y1, "%.1f") << "\" x2=\"" << Format(x2, "%.1f")
         << "\" y2=\"" << Format(y2, "%.1f") << "\" stroke=\"" << colour << "\" stroke-width=\"" << width << "\"/>\n";
  }

  void Rect(double x, double y, double w, double h, const char* colour) {
    out_ << "<rect x=\"" << Format(x, "%.1f") << "\" y=\"" << Format(y, "%.1f") << "\" width=\"" << Format(w, "%.1f")
         << "\" height=\"" << Format(std::max(h, 0.0), "%.1f") << "\" fill=\"" << colour << "\"/>\n";
  }

  void Raw(const std::string& element) { out_ << element << "\n"; }

  // Horizontal grid lines with labels for the value axis, and the axis titles.
  void ValueGrid(const Axis& axis) {
    for (double tick : axis.Ticks()) {
      const double y = axis.ToPixel(tick);
      Line(PlotLeft(), y, PlotRight(), y, "#DDDDDD");
      Text(PlotLeft() - 8, y + 4, Format(tick), "end");
    }
    Line(PlotLeft(), PlotTop(), PlotLeft(), PlotBottom(), "#333333");
    Line(PlotLeft(), PlotBottom(), PlotRight(), PlotBottom(), "#333333");
    const double middle = (PlotTop() + PlotBottom()) / 2;
    Text(20, middle, options_.y_label, "middle", 13, "normal", "rotate(-90 20 " + Format(middle, "%.1f") + ")");
    Text((PlotLeft() + PlotRight()) / 2, options_.height - 16, options_.x_label);
  }

  std::string Finish() {
    out_ << "</svg>\n";
    return out_.str();
  }

 private:
  const ChartOptions& options_;
  std::ostringstream out_;
};

}  // namespace

std::vector<double> LinearTicks(double lo, double hi, int count) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, count - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  // From the multiple at or below lo to the first at or above hi: the ticks cover [lo, hi].
  std::vector<double> ticks;
  const double first = std::floor(lo / step + 1e-9);
  for (int k = 0;; ++k) {
    const double v = (first + k) * step;
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    if (v >= hi - step * 1e-9) break;
  }
  return ticks;
}

std::string BarChartSvg(const ChartOptions& options, const std::vector<Bar>& bars) {
  SvgWriter svg(options);
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const Bar& bar : bars) {
    hi = std::max(hi, bar.value + bar.error);
    if (bar.value > 0) lo = std::min(lo, options.log_y ? bar.value * 0.5 : 0.0);
  }
  const Axis axis = ValueAxis(options.log_y ? lo : 0.0, hi * 1.08, options.log_y, svg.PlotBottom(), svg.PlotTop());
  svg.ValueGrid(axis);
  const double slot = (svg.PlotRight() - svg.PlotLeft()) / std::max<size_t>(1, bars.size());
  for (size_t k = 0; k < bars.size(); ++k) {
    const Bar& bar = bars[k];
    const double centre = svg.PlotLeft() + slot * (k + 0.5), width = slot * 0.6;
    const double top = axis.ToPixel(bar.value);
    svg.Rect(centre - width / 2, top, width, svg.PlotBottom() - top, kColours[k % kNumColours]);
    if (bar.error > 0) {
      const double upper = axis.ToPixel(bar.value + bar.error), lower = axis.ToPixel(bar.value - bar.error);
      svg.Line(centre, upper, centre, lower, "#222222", 1.5);
      svg.Line(centre - width / 6, upper, centre + width / 6, upper, "#222222", 1.5);
      svg.Line(centre - width / 6, lower, centre + width / 6, lower, "#222222", 1.5);
    }
    svg.Text(centre + width / 2 + 2, top - 6, Format(bar.value, "%.3g"), "start", 12);
    svg.Text(centre, svg.PlotBottom() + 20, bar.label);
  }
  return svg.Finish();
}

std::string LineChartSvg(const ChartOptions& options, const std::vector<LineSeries>& series) {
  SvgWriter svg(options);
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = 0;
  for (const LineSeries& s : series) {
    for (size_t k = 0; k < s.x.size(); ++k) {
      x_lo = std::min(x_lo, s.x[k]);
      x_hi = std::max(x_hi, s.x[k]);
      y_hi = std::max(y_hi, s.y[k]);
      if (s.y[k] > 0) y_lo = std::min(y_lo, s.y[k]);
    }
  }
  if (!(x_hi > x_lo)) {
    x_lo = std::isfinite(x_lo) ? x_lo - 1 : 0;
    x_hi = x_lo + 2;
  }
  const Axis y_axis =
      ValueAxis(options.log_y ? y_lo : 0.0, y_hi * 1.05, options.log_y, svg.PlotBottom(), svg.PlotTop());
  svg.ValueGrid(y_axis);
  Axis x_axis;
  x_axis.lo = x_lo;
  x_axis.hi = x_hi;
  x_axis.pixel_lo = svg.PlotLeft() + 10;
  x_axis.pixel_hi = svg.PlotRight() - 10;
  for (double tick : LinearTicks(x_lo, x_hi, 10)) {
    if (tick < x_lo || tick > x_hi) continue;
    const double x = x_axis.ToPixel(tick);
    svg.Line(x, svg.PlotBottom(), x, svg.PlotBottom() + 5, "#333333");
    svg.Text(x, svg.PlotBottom() + 20, Format(tick));
  }
  for (size_t s = 0; s < series.size(); ++s) {
    const char* colour = kColours[s % kNumColours];
    std::ostringstream points;
    for (size_t k = 0; k < series[s].x.size(); ++k) {
      points << Format(x_axis.ToPixel(series[s].x[k]), "%.1f") << "," << Format(y_axis.ToPixel(series[s].y[k]), "%.1f")
             << " ";
    }
    svg.Raw("<polyline fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"2\" points=\"" +
            points.str() + "\"/>");
    for (size_t k = 0; k < series[s].x.size(); ++k) {
      svg.Raw("<circle cx=\"" + Format(x_axis.ToPixel(series[s].x[k]), "%.1f") + "\" cy=\"" +
              Format(y_axis.ToPixel(series[s].y[k]), "%.1f") + "\" r=\"3\" fill=\"" + colour + "\"/>");
    }
    const double legend_y = svg.PlotTop() + 18 + 20 * s;
    svg.Line(svg.PlotRight() - 170, legend_y - 4, svg.PlotRight() - 146, legend_y - 4, colour, 3);
    svg.Text(svg.PlotRight() - 140, legend_y, series[s].name, "start");
  }
  return svg.Finish();
}

}  // namespace hexcal::plots

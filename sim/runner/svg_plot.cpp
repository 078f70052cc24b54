#include "sim/runner/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sim/runner/report_html.h"
#include "sim/runner/report_style.h"

namespace coopmap {
namespace {

using namespace report_style;

// ---- plots ------------------------------------------------------------------------------

// 1, 2 or 5 times a power of ten, at least `raw`.
double niceStep(double raw) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0) * mag;
}

// Decimals that show every multiple of `step` (1, 2 or 5 times a power of ten) exactly.
int decimalsFor(double step) {
  return std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
}

std::string formatFixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace

std::string renderSvgPlot(const std::vector<ReportSeries>& series, const PlotAxes& axes) {
  // Presentation attributes, not the page's CSS, so the SVG stands alone.
  const std::string kSeriesStyle =
      "fill=\"none\" stroke-width=\"1.8\" stroke-linejoin=\"round\" stroke-linecap=\"round\"";
  constexpr double kW = 720, kLeft = 64, kRight = 20, kTop = 14, kPlotH = 240;
  const double plot_w = kW - kLeft - kRight;

  // Ranges: x from min(0, first t) to the last t; y from min(0, lowest) to a nice top.
  double x_lo = 0, x_hi = -std::numeric_limits<double>::infinity();
  double y_lo = 0, y_hi = std::max(0.0, axes.y_max);
  for (const ReportSeries& sr : series)
    for (const auto& [t, v] : sr.points) {
      if (!std::isfinite(t) || !std::isfinite(v)) continue;
      x_lo = std::min(x_lo, t);
      x_hi = std::max(x_hi, t);
      y_lo = std::min(y_lo, v);
      y_hi = std::max(y_hi, v);
    }
  if (!(x_hi > x_lo)) x_hi = x_lo + 1.0;
  if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;
  const double x_step = niceStep((x_hi - x_lo) / 6.0);
  const double y_step = niceStep((y_hi - y_lo) / 5.0);
  y_lo = std::floor(y_lo / y_step + 1e-9) * y_step;
  y_hi = std::ceil(y_hi / y_step - 1e-9) * y_step;
  auto X = [&](double t) { return kLeft + (t - x_lo) / (x_hi - x_lo) * plot_w; };
  auto Y = [&](double v) { return kTop + (y_hi - v) / (y_hi - y_lo) * kPlotH; };

  // Legend rows below the x-axis label, wrapped to the plot's width.
  struct Entry {
    double x, y;
  };
  std::vector<Entry> entries;
  const double legend_top = kTop + kPlotH + 52;
  double lx = kLeft, ly = legend_top;
  for (const ReportSeries& sr : series) {
    const double w = 30 + 7.0 * static_cast<double>(sr.name.size() + (sr.points.empty() ? 10 : 0));
    if (lx > kLeft && lx + w > kW - kRight) {
      lx = kLeft;
      ly += 18;
    }
    entries.push_back({lx, ly});
    lx += w + 18;
  }
  const double height = (series.empty() ? legend_top - 10 : ly + 12);

  std::string svg;
  svg += "<svg class=\"plot\" viewBox=\"0 0 " + format("%.0f", kW) + " " + format("%.0f", height) +
         "\" font-family=\"Helvetica Neue, Helvetica, Arial, sans-serif\" font-size=\"12\" "
         "role=\"img\" aria-label=\"" +
         escapeHtml(axes.y_label) + " over " + escapeHtml(axes.x_label) +
         "\" xmlns=\"http://www.w3.org/2000/svg\">\n";
  // Grid, ticks and tick labels.
  const int y_decimals = decimalsFor(axes.y_percent ? 100 * y_step : y_step);
  for (double v = y_lo; v <= y_hi + 1e-9 * y_step; v += y_step) {
    const std::string y = format("%.1f", Y(v));
    svg += "<line class=\"grid\" stroke=\"#e6e6e6\" x1=\"" + format("%.1f", kLeft) + "\" x2=\"" +
           format("%.1f", kLeft + plot_w) + "\" y1=\"" + y + "\" y2=\"" + y + "\"/>";
    svg += "<line class=\"axis\" stroke=\"#222\" x1=\"" + format("%.1f", kLeft - 5) + "\" x2=\"" +
           format("%.1f", kLeft) + "\" y1=\"" + y + "\" y2=\"" + y + "\"/>";
    const double shown = std::abs(v) < 1e-9 * y_step ? 0.0 : (axes.y_percent ? 100 * v : v);
    svg += "<text x=\"" + format("%.1f", kLeft - 8) + "\" y=\"" + format("%.1f", Y(v) + 4) +
           "\" text-anchor=\"end\">" + formatFixed(shown, y_decimals) +
           (axes.y_percent ? " %" : "") + "</text>\n";
  }
  const int x_decimals = decimalsFor(x_step);
  for (double t = std::ceil(x_lo / x_step - 1e-9) * x_step; t <= x_hi + 1e-9 * x_step;
       t += x_step) {
    const std::string x = format("%.1f", X(t));
    svg += "<line class=\"axis\" stroke=\"#222\" x1=\"" + x + "\" x2=\"" + x + "\" y1=\"" +
           format("%.1f", kTop + kPlotH) + "\" y2=\"" + format("%.1f", kTop + kPlotH + 5) + "\"/>";
    svg += "<text x=\"" + x + "\" y=\"" + format("%.1f", kTop + kPlotH + 19) +
           "\" text-anchor=\"middle\">" +
           formatFixed(std::abs(t) < 1e-9 * x_step ? 0.0 : t, x_decimals) + "</text>\n";
  }
  // Axes and their labels.
  svg += "<polyline class=\"axis\" stroke=\"#222\" fill=\"none\" points=\"" +
         format("%.1f", kLeft) + "," + format("%.1f", kTop) + " " + format("%.1f", kLeft) + "," +
         format("%.1f", kTop + kPlotH) + " " + format("%.1f", kLeft + plot_w) + "," +
         format("%.1f", kTop + kPlotH) + "\"/>\n";
  svg += "<text x=\"" + format("%.1f", kLeft + plot_w / 2) + "\" y=\"" +
         format("%.1f", kTop + kPlotH + 38) + "\" text-anchor=\"middle\">" +
         escapeHtml(axes.x_label) + "</text>\n";
  svg += "<text transform=\"translate(16 " + format("%.1f", kTop + kPlotH / 2) +
         ") rotate(-90)\" text-anchor=\"middle\">" + escapeHtml(axes.y_label) + "</text>\n";
  // Reference lines.
  for (const auto& [v, text] : axes.reference) {
    if (!(v >= y_lo && v <= y_hi)) continue;
    const std::string y = format("%.1f", Y(v));
    svg += "<line class=\"ref\" stroke=\"#555\" stroke-dasharray=\"6 4\" x1=\"" +
           format("%.1f", kLeft) + "\" x2=\"" + format("%.1f", kLeft + plot_w) + "\" y1=\"" + y +
           "\" y2=\"" + y + "\"/>";
    // Labelled at the left, where a rising curve such as coverage is still low.
    svg +=
        "<text class=\"ref\" fill=\"#555\" stroke=\"#fff\" stroke-width=\"3\" "
        "paint-order=\"stroke\" x=\"" +
        format("%.1f", kLeft + 6) + "\" y=\"" + format("%.1f", Y(v) - 5) + "\">" +
        escapeHtml(text) + "</text>\n";
  }
  // Series: one polyline per finite run, a dot for a run of one point; dropping points that
  // move less than half a pixel from the last one kept.
  for (size_t i = 0; i < series.size(); ++i) {
    const std::string colour = hexColour(paletteColour(i));
    std::vector<std::pair<double, double>> run;
    auto flush = [&] {
      if (run.size() == 1)
        svg += "<circle cx=\"" + format("%.1f", run[0].first) + "\" cy=\"" +
               format("%.1f", run[0].second) + "\" r=\"3\" fill=\"" + colour + "\"/>\n";
      if (run.size() > 1) {
        svg +=
            "<polyline class=\"series\" " + kSeriesStyle + " stroke=\"" + colour + "\" points=\"";
        for (size_t k = 0; k < run.size(); ++k)
          svg +=
              (k ? " " : "") + format("%.1f", run[k].first) + "," + format("%.1f", run[k].second);
        svg += "\"/>\n";
      }
      run.clear();
    };
    const auto& pts = series[i].points;
    for (size_t k = 0; k < pts.size(); ++k) {
      const auto& [t, v] = pts[k];
      if (!std::isfinite(t) || !std::isfinite(v)) {
        flush();
        continue;
      }
      const std::pair<double, double> p(X(t), Y(v));
      const bool last = k + 1 == pts.size() || !std::isfinite(pts[k + 1].first) ||
                        !std::isfinite(pts[k + 1].second);
      if (run.empty() || last || std::abs(p.first - run.back().first) >= 0.5 ||
          std::abs(p.second - run.back().second) >= 0.5)
        run.push_back(p);
    }
    flush();
  }
  // Legend.
  for (size_t i = 0; i < series.size(); ++i) {
    const Entry& e = entries[i];
    svg += "<line class=\"series\" " + kSeriesStyle + " stroke=\"" + hexColour(paletteColour(i)) +
           "\" x1=\"" + format("%.1f", e.x) + "\" x2=\"" + format("%.1f", e.x + 24) + "\" y1=\"" +
           format("%.1f", e.y) + "\" y2=\"" + format("%.1f", e.y) + "\"/>";
    svg += "<text x=\"" + format("%.1f", e.x + 30) + "\" y=\"" + format("%.1f", e.y + 4) + "\">" +
           escapeHtml(series[i].name) + (series[i].points.empty() ? " (no data)" : "") +
           "</text>\n";
  }
  svg += "</svg>";
  return svg;
}

}  // namespace coopmap

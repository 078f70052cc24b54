// Line plots as inline SVG, for report.html (report_html.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace coopmap {

// One line of a plot.
struct ReportSeries {
  std::string name;                               // legend
  std::vector<std::pair<double, double>> points;  // (t s, value); non-finite points break the line
};

// Renders one line plot as a standalone <svg> element (720 px wide in its viewBox): axes
// with ticks and labels, one polyline per series (a dot for a single point), a legend below.
// `y_percent` labels the y axis in percent of the values (0.9 -> "90 %"); `reference` draws
// dashed horizontal lines at (value, label); `y_max` > 0 fixes the top of the y axis (the data
// may still raise it). x spans min(0, first t)..last t; y starts at 0 (lower if data are).
struct PlotAxes {
  std::string x_label = "time (s)";
  std::string y_label;
  bool y_percent = false;
  double y_max = 0.0;
  std::vector<std::pair<double, std::string>> reference;
};
std::string renderSvgPlot(const std::vector<ReportSeries>& series, const PlotAxes& axes);

}  // namespace coopmap
